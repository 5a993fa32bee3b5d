#include "moreau/fem/petsc/petsc_matrix.hpp"

namespace moreau {

bool set_petsc_matrix(petsc_plugin::LinearSolver& solver, const SparseMatrix& A, std::string& failure) {
  SparseMatrix compressed;
  const SparseMatrix* M = &A;
  if (!A.isCompressed()) {
    compressed = A;
    compressed.makeCompressed();
    M = &compressed;
  }
  if (solver.set_matrix(static_cast<int>(M->rows()), M->outerIndexPtr(), M->innerIndexPtr(), M->valuePtr(), failure))
    return true;
  failure = "PETSc could not set up the preconditioner: " + failure;
  return false;
}

}  // namespace moreau
