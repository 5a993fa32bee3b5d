#pragma once
// Checking a flow source's Jacobian (an immersed solid's or rigid body's coupling) against central
// differences of its residual.
#include <algorithm>
#include <utility>
#include <vector>

#include "moreau/fem/flow/navier_stokes.hpp"

namespace moreau::test {

/// The largest relative difference |J_col - D_col| / |J_col| over the columns of the source's
/// Jacobian at x that are not zero, D_col the central difference with step h of its residual on
/// the free dofs; and how many columns were compared. With `normwise`, the differences are
/// measured against the largest column's norm instead (for residuals whose round-off, divided by
/// h, swamps the weakest columns).
inline std::pair<Real, int> source_jacobian_against_differences(const FlowSource& source, const NavierStokesModel& m,
                                                                const VectorX& x, const FlowTimeStep& step, Real h,
                                                                bool normwise = false) {
  auto residual = [&](const VectorX& at) {
    VectorX R = VectorX::Zero(m.dof_count());
    source.add(at, step, R, nullptr);
    VectorX free(m.free_count);
    for (Index d = 0; d < m.dof_count(); ++d)
      if (m.free_index[d] >= 0) free[m.free_index[d]] = R[d];
    return free;
  };
  VectorX R = VectorX::Zero(m.dof_count());
  std::vector<Eigen::Triplet<Real, int>> entries;
  source.add(x, step, R, &entries);
  if (!R.allFinite()) return {kInfinity, 0};
  SparseMatrix J(m.free_count, m.free_count);
  J.setFromTriplets(entries.begin(), entries.end());
  int columns = 0;
  Real worst = 0, largest = 0;
  for (int k = 0; k < J.outerSize(); ++k) largest = std::max(largest, J.col(k).norm());
  for (Index d = 0; d < m.dof_count(); ++d) {
    const Index column = m.free_index[d];
    if (column < 0 || J.col(column).norm() == 0) continue;
    VectorX plus = x, minus = x;
    plus[d] += h;
    minus[d] -= h;
    const VectorX difference = (residual(plus) - residual(minus)) / (2 * h);
    const VectorX exact = J.col(column);
    worst = std::max(worst, (exact - difference).norm() / (normwise ? largest : exact.norm()));
    ++columns;
  }
  return {worst, columns};
}

}  // namespace moreau::test
