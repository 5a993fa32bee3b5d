#include "moreau/solvers/xpbd/contact_blocks.hpp"

#include <algorithm>
#include <cmath>

namespace moreau {

namespace {

// How much a sweep moved the rows: max_r |(K (x - start))_r|, the change of each row's value
// (depth or slip, m; or velocity, m/s) that the sweep's impulses cause. It ignores the directions
// in which a singular block's impulses can drift without moving the bodies (four corners of a face
// share three independent normal directions), where Gauss-Seidel converges slowly but nothing
// physical changes.
Real largest_row_change(const BlockMatrix& K, const RowValues& start, const RowValues& x, int rows) {
  RowValues dx{};
  for (int r = 0; r < rows; ++r) dx[r] = x[r] - start[r];
  Real largest = 0;
  for (int r = 0; r < rows; ++r) {
    Real change = 0;
    for (int q = 0; q < rows; ++q) change += K[r][q] * dx[q];
    largest = std::max(largest, std::abs(change));
  }
  return largest;
}

}  // namespace

BlockMatrix effective_mass_block(const InverseMass& a, const InverseMass& b, const ContactRows& rows) {
  const int n = rows.size();
  std::array<Vec3, ContactRows::kMaxRows> ua, ub, Iua, Iub;
  for (int r = 0; r < n; ++r) {
    ua[r] = rows.offset_a[r].cross(rows.direction[r]);
    ub[r] = rows.offset_b[r].cross(rows.direction[r]);
    Iua[r] = a.angular * ua[r];
    Iub[r] = b.angular * ub[r];
  }
  const Real linear = a.linear + b.linear;
  BlockMatrix K{};
  for (int r = 0; r < n; ++r)
    for (int q = r; q < n; ++q)
      K[r][q] = K[q][r] = rows.direction[r].dot(rows.direction[q]) * linear + ua[r].dot(Iua[q]) + ub[r].dot(Iub[q]);
  return K;
}

PositionBlockSolution solve_position_block(const ContactRows& rows, const BlockMatrix& K) {
  const int n = rows.size(), k = rows.points;
  RowValues x{};  // local, so that the sweeps' stores cannot alias K or C
  const Real mu = rows.static_friction;
  auto residual = [&](int r) {
    Real v = rows.C[r];
    for (int q = 0; q < n; ++q) v += K[r][q] * x[q];
    return v;
  };
  Real scale = 0;  // m: the largest depth or slip of the block
  for (int r = 0; r < n; ++r) scale = std::max(scale, std::abs(rows.C[r]));
  const Real tolerance = kBlockTolerance * scale + kPositionFloor;
  auto sweeps = [&](bool friction, int max_sweeps) {
    for (int sweep = 0; sweep < max_sweeps; ++sweep) {
      const RowValues start = x;
      for (int j = 0; j < k; ++j) {
        const int rn = 3 * j;
        if (K[rn][rn] > 0) x[rn] = std::max(Real(0), x[rn] - residual(rn) / K[rn][rn]);
        if (!friction) continue;
        for (int r = rn + 1; r < rn + 3; ++r)
          if (K[r][r] > 0) x[r] -= residual(r) / K[r][r];
        // Project onto the friction cone |x_t| <= mu_s x_n.
        const Real ft = std::sqrt(x[rn + 1] * x[rn + 1] + x[rn + 2] * x[rn + 2]);
        const Real bound = mu * x[rn];
        if (ft > bound) {
          x[rn + 1] *= bound / ft;
          x[rn + 2] *= bound / ft;
        }
      }
      const Real largest_change = largest_row_change(K, start, x, n);
      if (largest_change <= tolerance) return;
    }
  };
  // A few sweeps decide most blocks: a resting contact's friction lies well inside its cone, a
  // sliding one's on it at every pushing point. A block left between the two (some points on the
  // cone, some inside) is swept to convergence before it is judged, so that the judgement does not
  // depend on the order of the rows (a box on a slope steeper than its friction angle was held
  // for its first step, or not, depending on the slope's direction).
  auto on_cone = [&](int j) {
    const Real ft = std::sqrt(x[3 * j + 1] * x[3 * j + 1] + x[3 * j + 2] * x[3 * j + 2]);
    return ft >= (1 - 1e-9) * mu * x[3 * j];
  };
  sweeps(true, kFirstSweeps);
  int pushing = 0, limited = 0;
  for (int j = 0; j < k; ++j)
    if (x[3 * j] > 0) {
      ++pushing;
      limited += on_cone(j) ? 1 : 0;
    }
  if (limited > 0 && limited < pushing) sweeps(true, kMaxBlockSweeps);
  // Static friction holds only inside the cone (Mueller 2020, eq. 27), judged for the manifold as
  // a whole: when every pushing point's friction sits on its cone, the manifold slides, the
  // friction rows are dropped and the velocity pass applies dynamic friction instead. (Single
  // corners on the cone while others hold is a box that sticks.)
  bool sliding = false;
  for (int j = 0; j < k; ++j) {
    if (x[3 * j] <= 0) continue;
    sliding = on_cone(j);
    if (!sliding) break;
  }
  if (sliding) {
    for (int j = 0; j < k; ++j) x[3 * j + 1] = x[3 * j + 2] = 0;
    sweeps(false, kMaxBlockSweeps);
  }
  return {x, sliding};
}

RowValues solve_velocity_block(const BlockMatrix& K, const RowValues& v0, const RowValues& target,
                               const RowValues& bound, int rows, Real speed) {
  RowValues x{};
  const Real tolerance = kBlockTolerance * speed + kVelocityFloor;
  for (int sweep = 0; sweep < kMaxBlockSweeps; ++sweep) {
    const RowValues start = x;
    for (int r = 0; r < rows; r += 3) {
      for (int q = r; q < r + 3; ++q) {
        if (K[q][q] <= 0) continue;
        Real v = v0[q] - (q == r ? target[r] : 0);
        for (int p = 0; p < rows; ++p) v += K[q][p] * x[p];
        x[q] -= v / K[q][q];
      }
      const Real ft = std::sqrt(x[r + 1] * x[r + 1] + x[r + 2] * x[r + 2]);
      if (ft > bound[r]) {
        x[r + 1] *= bound[r] / ft;
        x[r + 2] *= bound[r] / ft;
      }
    }
    const Real largest_change = largest_row_change(K, start, x, rows);
    if (largest_change <= tolerance) break;
  }
  return x;
}

}  // namespace moreau
