#pragma once
// How the rows of a distributed system are numbered for PETSc. PETSc gives each rank one
// contiguous range of rows; the engine numbers its unknowns its own way and says which rank owns
// each (UnknownLayout::owner). PETSc's numbering takes rank 0's unknowns first, then rank 1's, ...,
// each rank's in the engine's order, so every rank computes the same numbering from the owners.
#include <petscsys.h>

#include <vector>

namespace moreau::petsc_plugin {

struct RowDistribution {
  /// `owner`: per engine unknown, its rank (0 .. ranks - 1); `rank`: this process's.
  RowDistribution(const std::vector<int>& owner, int rank, int ranks);

  std::vector<PetscInt> petsc_index;  // per engine unknown, its PETSc row
  std::vector<int> owned;             // this rank's engine unknowns, in PETSc order
  PetscInt first = 0;                 // this rank's first PETSc row
  int rank = 0;
};

}  // namespace moreau::petsc_plugin
