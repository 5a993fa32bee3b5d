#pragma once
// Handing an Eigen sparse matrix to a PETSc plugin solver.
#include <string>

#include "moreau/fem/core/cell_sparsity.hpp"
#include "moreau/fem/petsc/petsc_plugin_api.hpp"

namespace moreau {

/// Gives `A` (compressed first if it is not) to `solver`; false, with `failure` set, if PETSc cannot
/// set up the preconditioner for it.
bool set_petsc_matrix(petsc_plugin::LinearSolver& solver, const SparseMatrix& A, std::string& failure);

}  // namespace moreau
