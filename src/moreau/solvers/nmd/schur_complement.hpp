#pragma once
// The Schur complement A = G W G^T + S of a set of an NMD system's rows (nmd_system.hpp), sparse,
// factored by Cholesky: Eigen's SimplicialLDLT (AMD ordering) while A is small, CHOLMOD's
// supernodal LL^T (BLAS-3 on the fill of a soft body's rows) beyond kSupernodalNonZeros. On a
// soft body of 2462 tetrahedra (14772 rows, 2.2M nonzeros) a step's factorisation took 8 s with
// the first and 1 s with the second; on a 480-tetrahedron bar, whose many small solves dominate,
// CHOLMOD's per-solve overhead made the run 1.4 times slower. A is symmetric positive definite when
// S > 0 or G has full row rank; rows of a block are coupled through their block's S, rows of
// different blocks through the ends they share. The symbolic analysis is kept while the pattern
// of A does not change (the same rows between the same ends from one solve to the next).
//
// A row may be clamped: its row and column of A are replaced by the identity's, so its value is
// fixed by the right-hand side while the pattern stays (the active-set loop of the direct method).
#include <Eigen/CholmodSupport>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <vector>

#include "moreau/solvers/nmd/nmd_system.hpp"

namespace moreau {

class SchurComplement {
 public:
  static constexpr Real kRegularisation = 1e-12;  // relative, on every diagonal
  static constexpr Index kSupernodalNonZeros = 200000;
  using Sparse = Eigen::SparseMatrix<Real>;

  /// Builds G (rows x dofs), W G^T and A over `rows` (system row indices, in order).
  void build(const NmdSystem& system, const std::vector<Index>& rows, Index dofs);
  /// Factors A with the rows marked in `clamped` (indexed like `rows`) replaced by identity rows
  /// (nothing to do when A and the clamps are those of the last factorisation); false when A is
  /// not positive definite.
  bool factorize(const std::vector<char>& clamped);
  /// A^-1 b for the factored matrix.
  VectorX solve(const VectorX& b) const { return supernodal_ ? VectorX(cholmod_.solve(b)) : VectorX(ldlt_.solve(b)); }

  /// G x for a velocity vector x (one value per row).
  VectorX rate(const std::vector<Real>& v) const;
  /// v += W G^T l.
  void apply(const VectorX& l, std::vector<Real>& v) const;
  /// A l (the unclamped A) and S l.
  VectorX product(const VectorX& l) const { return A_ * l; }
  VectorX sigma_product(const VectorX& l) const { return S_ * l; }
  Index size() const { return static_cast<Index>(A_.rows()); }

 private:
  Sparse G_, WGt_, S_, A_, clamped_A_;
  Eigen::SimplicialLDLT<Sparse> ldlt_;
  Eigen::CholmodSupernodalLLT<Sparse, Eigen::Lower> cholmod_;
  bool supernodal_ = false;  // which of the two holds the factorisation
  std::vector<Index> pattern_outer_, pattern_inner_;  // of the analysed pattern
  bool analysed_ = false;
  std::vector<char> factored_clamps_;  // of the current factorisation of this A
  bool factored_ = false, factored_ok_ = false;
};

}  // namespace moreau
