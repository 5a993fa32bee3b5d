#pragma once
// The engine's view of MPI (petsc_plugin_api.hpp's Communicator) on PETSc's world communicator:
// all of MPI_COMM_WORLD under mpirun, this process alone otherwise.
#include "moreau/fem/petsc/petsc_plugin_api.hpp"

namespace moreau::petsc_plugin {

class MpiWorld final : public Communicator {
 public:
  int rank() const override;
  int size() const override;
  void all_gather(const double* mine, const int* counts, double* all) const override;
};

}  // namespace moreau::petsc_plugin
