#pragma once
// Sparse direct solves of the FEM engine's tangent systems through Eigen's SuiteSparse wrappers.
// The tangent of a hyperelastic solid is symmetric; near equilibrium and with enough Dirichlet
// conditions it is positive definite and CHOLMOD's supernodal Cholesky factorizes it. Where it is
// not (buckling, a free-floating body's rigid modes, compression past a limit point) the
// factorization reports it and UMFPACK's LU takes over. The symbolic analysis is done once per
// sparsity pattern and reused by every later factorization.
#include <Eigen/CholmodSupport>
#include <Eigen/UmfPackSupport>
#include <memory>
#include <string>
#include <vector>

#include "moreau/fem/solids/fem_model.hpp"

namespace moreau {

/// UMFPACK's LU of a square sparse matrix; the symbolic analysis is done for the first matrix and
/// reused for every later one with the same sparsity (a matrix with another pattern, such as a
/// flow's with an immersed solid that moved to other cells, is analysed again).
class SparseLuSolver {
 public:
  SparseLuSolver();
  /// False if the matrix is singular.
  bool factorize(const SparseMatrix& A);
  VectorX solve(const VectorX& b) const { return lu_.solve(b); }

 private:
  Eigen::UmfPackLU<SparseMatrix> lu_;
  std::vector<int> analyzed_outer_, analyzed_inner_;  // the analysed pattern (compressed column starts, rows)
};

class SparseSymmetricSolver {
 public:
  SparseSymmetricSolver();
  /// Factorizes K; false if neither Cholesky nor LU succeeds (a singular K). A K that is not
  /// symmetric (`symmetric` false) goes to LU directly.
  bool factorize(const SparseMatrix& K, bool symmetric = true);
  /// Solves K x = b with the last factorization.
  VectorX solve(const VectorX& b) const;
  /// "cholmod" or "umfpack": what factorized the last K.
  const std::string& method() const { return method_; }

 private:
  Eigen::CholmodSupernodalLLT<SparseMatrix, Eigen::Lower> cholesky_;
  SparseLuSolver lu_;
  bool cholesky_analyzed_ = false;
  std::string method_;
};

}  // namespace moreau
