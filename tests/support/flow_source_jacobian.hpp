#pragma once
// Checking a flow source's Jacobian (an immersed solid's or rigid body's coupling) against central
// differences of its residual.
#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "moreau/fem/core/cell_sparsity.hpp"
#include "moreau/fem/flow/flow_source_assembly.hpp"
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

/// A 2D fluid state x at t_n+1 and x_n at t_n with smooth, swirling velocities of order 1 m/s (and
/// zero pressure), for checking a source's Jacobian away from any special state.
/// The whole flow's Jacobian with `source` in it (assemble_flow_with_source: sparse part plus
/// U V^T) against central differences of its residual, over the velocity columns of the fluid
/// nodes within `radius` of `centre`: the largest difference against the largest column's norm,
/// and how many columns were compared. Hold tau fixed (model.fixed_tau) for an exact comparison.
inline std::pair<Real, int> flow_with_source_jacobian_against_differences(const NavierStokesModel& m, const FlowSource& source,
                                                                           const VectorX& x, const FlowTimeStep& step,
                                                                           Real h, const Vec3& centre, Real radius) {
  double seconds = 0;
  auto residual = [&](const VectorX& at) {
    VectorX R;
    assemble_flow_with_source(m, at, step, source, {}, R, nullptr, nullptr, seconds);
    return gather_free(m.free_index, m.free_count, R);
  };
  VectorX R;
  SparseMatrix J;
  FlowLowRank low_rank;
  assemble_flow_with_source(m, x, step, source, {}, R, &J, &low_rank, seconds);
  Eigen::MatrixXd UV = Eigen::MatrixXd::Zero(m.free_count, m.free_count);
  if (low_rank.U.cols() > 0) UV = low_rank.U * low_rank.V.transpose();
  Real largest = 0;
  for (int k = 0; k < J.outerSize(); ++k) largest = std::max(largest, (VectorX(J.col(k)) + UV.col(k)).norm());
  Real worst = 0;
  int columns = 0;
  for (Index n = 0; n < m.mesh.node_count(); ++n) {
    if ((m.mesh.nodes[n] - centre).norm() > radius) continue;
    for (int i = 0; i < m.dim(); ++i) {
      const Index d = m.dof(n, i), column = m.free_index[d];
      if (column < 0) continue;
      VectorX plus = x, minus = x;
      plus[d] += h;
      minus[d] -= h;
      const VectorX difference = (residual(plus) - residual(minus)) / (2 * h);
      worst = std::max(worst, (VectorX(J.col(column)) + UV.col(column) - difference).norm() / largest);
      ++columns;
    }
  }
  return {worst, columns};
}

inline void swirling_velocities_2d(const NavierStokesModel& m, VectorX& x, VectorX& x_n) {
  x = VectorX::Zero(m.dof_count());
  x_n = VectorX::Zero(m.dof_count());
  for (Index n = 0; n < m.mesh.node_count(); ++n) {
    const Vec3& p = m.mesh.nodes[n];
    x[m.dof(n, 0)] = std::sin(3 * p.x() + 1) * std::cos(2 * p.y());
    x[m.dof(n, 1)] = 0.7 * std::cos(4 * p.x()) * std::sin(3 * p.y() + 0.5);
    x_n[m.dof(n, 0)] = 0.5 * std::cos(2 * p.y() + 0.3);
    x_n[m.dof(n, 1)] = 0.4 * std::sin(3 * p.x());
  }
}

}  // namespace moreau::test
