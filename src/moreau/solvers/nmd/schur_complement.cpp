#include "moreau/solvers/nmd/schur_complement.hpp"

#include <algorithm>

namespace moreau {

void SchurComplement::build(const NmdSystem& system, const std::vector<Index>& rows, Index dofs) {
  const Index m = static_cast<Index>(rows.size());
  // Each system row's position in this set (-1: not in it), to couple rows of one block.
  std::vector<Index> local(system.row_count(), -1);
  for (Index i = 0; i < m; ++i) local[rows[i]] = i;
  std::vector<Eigen::Triplet<Real>> g, wg, s;
  for (Index i = 0; i < m; ++i) {
    const Index row = rows[i];
    const NmdBlock& b = system.blocks[system.row_block[row]];
    const Real* J = system.jacobian.data() + system.jacobian_offset[row];
    const Real* W = system.weighted.data() + system.jacobian_offset[row];
    const VelocityEnd* end = system.ends_of(b);
    for (int e = 0; e < b.ends; ++e) {
      for (int c = 0; c < end[e].size; ++c) {
        if (J[c] != 0) g.emplace_back(i, end[e].dof + c, J[c]);
        if (W[c] != 0) wg.emplace_back(end[e].dof + c, i, W[c]);
      }
      J += end[e].size;
      W += end[e].size;
    }
    // S: the block's full compliance for equality blocks, the diagonal otherwise.
    const int r = row - b.first_row;
    if (b.kind == NmdBlockKind::equality) {
      for (int t = 0; t < b.rows; ++t) {
        const Index other = local[b.first_row + t];
        const Real value = system.sigma_block[b.matrix + r * b.rows + t];
        if (other >= 0 && value != 0) s.emplace_back(i, other, value);
      }
    } else if (system.sigma[row] != 0) {
      s.emplace_back(i, i, system.sigma[row]);
    }
    s.emplace_back(i, i, 0.0);  // every diagonal in the pattern, so clamping keeps it
  }
  G_.resize(m, dofs);
  G_.setFromTriplets(g.begin(), g.end());
  WGt_.resize(dofs, m);
  WGt_.setFromTriplets(wg.begin(), wg.end());
  S_.resize(m, m);
  S_.setFromTriplets(s.begin(), s.end());
  A_ = (G_ * WGt_).pruned(0.0) + S_;
  A_.makeCompressed();
  factored_ = false;
  // Hard rows (S = 0) that repeat others (a box's four corners on a plane, a closed loop of
  // joints) make A singular; 1e-12 of each diagonal regularises them without changing what a
  // regular system solves to beyond round-off. A row no end of which can move gets a unit
  // diagonal and no impulse effect.
  for (Index j = 0; j < A_.outerSize(); ++j)
    for (Sparse::InnerIterator it(A_, j); it; ++it)
      if (it.row() == it.col()) it.valueRef() = it.value() > 0 ? it.value() * (1 + kRegularisation) : Real(1);
}

bool SchurComplement::factorize(const std::vector<char>& clamped) {
  if (factored_ && clamped == factored_clamps_) return factored_ok_;
  factored_ = true;
  factored_clamps_ = clamped;
  clamped_A_ = A_;
  for (Index j = 0; j < clamped_A_.outerSize(); ++j)
    for (Sparse::InnerIterator it(clamped_A_, j); it; ++it)
      if (clamped[it.row()] || clamped[it.col()]) it.valueRef() = it.row() == it.col() ? 1 : 0;
  const Index* outer = clamped_A_.outerIndexPtr();
  const Index* inner = clamped_A_.innerIndexPtr();
  const bool same = analysed_ && pattern_outer_.size() == static_cast<size_t>(clamped_A_.outerSize() + 1) &&
                    pattern_inner_.size() == static_cast<size_t>(clamped_A_.nonZeros()) &&
                    std::equal(pattern_outer_.begin(), pattern_outer_.end(), outer) &&
                    std::equal(pattern_inner_.begin(), pattern_inner_.end(), inner);
  if (!same) {
    supernodal_ = clamped_A_.nonZeros() > kSupernodalNonZeros;
    if (supernodal_)
      cholmod_.analyzePattern(clamped_A_);
    else
      ldlt_.analyzePattern(clamped_A_);
    pattern_outer_.assign(outer, outer + clamped_A_.outerSize() + 1);
    pattern_inner_.assign(inner, inner + clamped_A_.nonZeros());
    analysed_ = true;
  }
  if (supernodal_) {
    cholmod_.factorize(clamped_A_);
    factored_ok_ = cholmod_.info() == Eigen::Success;
  } else {
    ldlt_.factorize(clamped_A_);
    factored_ok_ = ldlt_.info() == Eigen::Success && (ldlt_.vectorD().array() > 0).all();
  }
  return factored_ok_;
}

VectorX SchurComplement::rate(const std::vector<Real>& v) const {
  return G_ * Eigen::Map<const VectorX>(v.data(), static_cast<Index>(v.size()));
}

void SchurComplement::apply(const VectorX& l, std::vector<Real>& v) const {
  Eigen::Map<VectorX>(v.data(), static_cast<Index>(v.size())) += WGt_ * l;
}

}  // namespace moreau
