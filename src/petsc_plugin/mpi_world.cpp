#include "mpi_world.hpp"

#include <petscsys.h>

#include <vector>

#include "petsc_call.hpp"

namespace moreau::petsc_plugin {

int MpiWorld::rank() const {
  int rank = 0;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  return rank;
}

int MpiWorld::size() const {
  int size = 1;
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  return size;
}

void MpiWorld::all_gather(const double* mine, const int* counts, double* all) const {
  const int ranks = size();
  std::vector<int> displacements(ranks, 0);
  for (int r = 1; r < ranks; ++r) displacements[r] = displacements[r - 1] + counts[r - 1];
  if (MPI_Allgatherv(mine, counts[rank()], MPI_DOUBLE, all, counts, displacements.data(), MPI_DOUBLE,
                     PETSC_COMM_WORLD) != MPI_SUCCESS)
    throw PetscFailure("MPI_Allgatherv failed");
}

}  // namespace moreau::petsc_plugin
