#include "moreau/solvers/nmd/nmd_system.hpp"

#include <algorithm>
#include <cmath>

namespace moreau {

namespace {

constexpr Real kInfinity = std::numeric_limits<Real>::infinity();

}  // namespace

void NmdBlockInput::resize(int rows, int end_count) {
  end.assign(end_count, VelocityEnd{});
  jacobian.assign(6 * static_cast<std::size_t>(rows) * end_count, 0);
  C.setZero(rows);
  known.setZero(rows);
  target.setZero(rows);
  lower.setConstant(rows, -kInfinity);
  upper.setConstant(rows, kInfinity);
  compliance.setZero(rows, rows);
  level.fill(RowLevel::position);
  kind = NmdBlockKind::equality;
  damping_time = 0;
  damper_rate = 0;
  static_friction = dynamic_friction = restitution = 0;
  memory = nullptr;
  memory_rows = 0;
}

void NmdSystem::clear() {
  blocks.clear();
  block_ends.clear();
  jacobian_offset.clear();
  row_block.clear();
  jacobian.clear();
  weighted.clear();
  rhs.clear();
  lower.clear();
  upper.clear();
  sigma.clear();
  diagonal.clear();
  impulse.clear();
  sigma_block.clear();
  inverse.clear();
}

void NmdSystem::add(const NmdBlockInput& in, const VelocitySpace& space, Real h, const NmdSettings& settings) {
  const int R = in.rows();
  NmdBlock block;
  block.kind = in.kind;
  block.rows = R;
  block.ends = in.ends();
  block.first_row = row_count();
  block.first_end = static_cast<Index>(block_ends.size());
  block_ends.insert(block_ends.end(), in.end.begin(), in.end.end());
  for (Index e = block.first_end; e < static_cast<Index>(block_ends.size()); ++e) block_ends[e].moves = space.moves(block_ends[e]);
  block.memory = in.memory;
  block.memory_rows = in.memory_rows;

  // SPOOK coefficients with d = tau / h, tau at least settings.stabilization steps.
  const Real d = std::max(in.damping_time / h, settings.stabilization);
  const Real a = 4 / (h * (1 + 4 * d)), b = 1 / (1 + 4 * d), spook = 4 / (h * h * (1 + 4 * d));
  // S per row: position rows eps 4 / (h^2 (1 + 4d)); velocity and friction rows eps / h.
  NmdBlockInput::Vector scale(R);
  for (int r = 0; r < R; ++r) scale[r] = in.level[r] == RowLevel::position ? spook : 1 / h;

  NmdBlockInput::Matrix A = NmdBlockInput::Matrix::Zero(R, R);
  const Index first_entry = static_cast<Index>(jacobian.size());
  for (int r = 0; r < R; ++r) {
    jacobian_offset.push_back(static_cast<Index>(jacobian.size()));
    row_block.push_back(static_cast<Index>(blocks.size()));
    for (int e = 0; e < in.ends(); ++e) {
      const int size = in.end[e].size;  // the world's end keeps no entries
      if (size == 0) continue;
      const Real* J = in.at(r, e);
      Real W[6];
      space.apply_inverse_mass(in.end[e], J, W);
      jacobian.insert(jacobian.end(), J, J + size);
      weighted.insert(weighted.end(), W, W + size);
    }
  }
  // A = G W G^T + S over the block.
  const Index stride = (static_cast<Index>(jacobian.size()) - first_entry) / R;
  for (int r = 0; r < R; ++r)
    for (int s = 0; s < R; ++s) {
      Real value = 0;
      for (Index k = 0; k < stride; ++k)
        value += jacobian[first_entry + r * stride + k] * weighted[first_entry + s * stride + k];
      A(r, s) = value;
    }
  // An impact (a contact closing faster than the restitution threshold within this step) is a
  // rigid collision with Newton's restitution law: its normal row drops the contact compliance,
  // which would otherwise absorb the rebound within the damping time.
  NmdBlockInput::Matrix compliance = in.damper_rate > 0 ? NmdBlockInput::Matrix(A / in.damper_rate) : in.compliance;
  bool impact = false;
  if (in.kind == NmdBlockKind::contact && in.restitution > 0) {
    const Real closing = rate(block, block.first_row, space.v) + in.known[0];
    impact = closing < -settings.restitution_threshold && in.C[0] + h * closing <= 0;
  }
  if (impact) compliance(0, 0) = 0;
  for (int r = 0; r < R; ++r)
    for (int s = 0; s < R; ++s) A(r, s) += 0.5 * (scale[r] + scale[s]) * compliance(r, s);

  for (int r = 0; r < R; ++r) {
    // dC/dt at the step's start, with the part from ends outside the velocity vector.
    const Real rate = this->rate(block, block.first_row + r, space.v) + in.known[r];
    Real target = 0;  // what dC/dt + (S l)_r should be after the solve
    switch (in.level[r]) {
      case RowLevel::position: target = -a * in.C[r] + b * rate; break;
      case RowLevel::velocity: target = in.target[r]; break;
      case RowLevel::friction: target = 0; break;
    }
    if (in.kind == NmdBlockKind::contact && r == 0) {
      // A speculative contact may close its gap within the step, no further; an impact faster
      // than the threshold that closes the gap this step leaves at e times its speed.
      // An adhesive contact (lower bound below 0) is held by its spring instead.
      if (in.C[r] > 0 && in.lower[r] >= 0) target = -in.C[r] / h;
      if (impact) target = std::max(target, -in.restitution * rate);
    }
    rhs.push_back(target - in.known[r]);
    sigma.push_back(scale[r] * compliance(r, r));
    diagonal.push_back(A(r, r));
    lower.push_back(in.lower[r] * h);
    upper.push_back(in.upper[r] * h);
    impulse.push_back(0);
  }

  if (in.kind == NmdBlockKind::contact && R == 3) {
    Real slip2 = 0;
    for (int r = 1; r < 3; ++r) {
      const Real rate = this->rate(block, block.first_row + r, space.v) + in.known[r];
      slip2 += rate * rate;
    }
    block.friction = slip2 > settings.sliding_speed * settings.sliding_speed ? in.dynamic_friction : in.static_friction;
  }
  if (in.kind == NmdBlockKind::equality) {
    block.matrix = static_cast<Index>(inverse.size());
    // An equality block between immovable ends with no compliance has a singular matrix: its
    // pseudo-inverse leaves the part it cannot move alone.
    Eigen::LDLT<NmdBlockInput::Matrix> ldlt(A);
    const bool regular = ldlt.info() == Eigen::Success && ldlt.isPositive() &&
                         ldlt.vectorD().minCoeff() > 1e-12 * std::max(Real(1e-300), ldlt.vectorD().maxCoeff());
    const NmdBlockInput::Matrix inv =
        regular ? NmdBlockInput::Matrix(ldlt.solve(NmdBlockInput::Matrix::Identity(R, R)))
                : NmdBlockInput::Matrix(A.completeOrthogonalDecomposition().pseudoInverse());
    for (int r = 0; r < R; ++r)
      for (int s = 0; s < R; ++s) {
        inverse.push_back(inv(r, s));
        sigma_block.push_back(0.5 * (scale[r] + scale[s]) * compliance(r, s));
      }
  }
  blocks.push_back(block);
}

}  // namespace moreau
