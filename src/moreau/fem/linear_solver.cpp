#include "moreau/fem/linear_solver.hpp"

namespace moreau {

SparseSymmetricSolver::SparseSymmetricSolver() {
  // An indefinite tangent is an expected outcome (UMFPACK takes over), not a warning to print.
  cholesky_.cholmod().print = 0;
}

bool SparseSymmetricSolver::factorize(const SparseMatrix& K, bool symmetric) {
  if (symmetric && !cholesky_analyzed_) {
    cholesky_.analyzePattern(K);
    cholesky_analyzed_ = true;
  }
  if (symmetric) cholesky_.factorize(K);
  if (symmetric && cholesky_.info() == Eigen::Success) {
    method_ = "cholmod";
    return true;
  }
  method_ = "umfpack";
  return lu_.factorize(K);
}

bool SparseLuSolver::factorize(const SparseMatrix& A) {
  if (!analyzed_) {
    lu_.analyzePattern(A);
    analyzed_ = true;
  }
  lu_.factorize(A);
  return lu_.info() == Eigen::Success;
}

VectorX SparseSymmetricSolver::solve(const VectorX& b) const {
  if (method_ == "cholmod") return cholesky_.solve(b);
  return lu_.solve(b);
}

}  // namespace moreau
