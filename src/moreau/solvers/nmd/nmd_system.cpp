#include "moreau/solvers/nmd/nmd_system.hpp"

#include <algorithm>
#include <array>
#include <cassert>
#include <cstring>
#include <cmath>

namespace moreau {

namespace {

Vec3 end_vector(const std::vector<Real>& v, const VelocityEnd& e) { return Vec3(v[e.dof], v[e.dof + 1], v[e.dof + 2]); }

// A = G W G^T and the rates G v of a grain pair's rows (GrainPairRows), ends (v_i, v_j, w_i, w_j).
void grain_pair_system(const GrainPairRows& g, const VelocityEnd* end, const std::vector<Real>& v,
                       NmdBlockInput::Matrix& A, NmdBlockInput::Vector& rate) {
  const Real linear = g.inv_mass[0] + g.inv_mass[1];
  const Real lever = g.arm[0] * g.arm[0] * g.inv_inertia[0] + g.arm[1] * g.arm[1] * g.inv_inertia[1];
  const Real turning = g.inv_inertia[0] + g.inv_inertia[1];
  // fill() reads A's diagonal and its normal column alone: the normal row is uncoupled from the
  // others (t . n = 0, no spin columns), so the rest of the column is zero.
  A(0, 0) = linear;
  A(1, 1) = A(2, 2) = linear + lever;
  A(3, 3) = A(4, 4) = A(5, 5) = turning;
  const std::array<Vec3, 3> turning_direction{g.t1, g.t2, g.n};
  const Vec3 dv = end_vector(v, end[0]) - end_vector(v, end[1]);
  const Vec3 wi = end_vector(v, end[2]), wj = end_vector(v, end[3]);
  const Vec3 u = g.arm[0] * wi + g.arm[1] * wj;
  rate[0] = g.n.dot(dv);
  rate[1] = g.t1.dot(dv) - g.t2.dot(u);
  rate[2] = g.t2.dot(dv) + g.t1.dot(u);
  for (int k = 0; k < 3; ++k) rate[3 + k] = turning_direction[k].dot(wi - wj);
}

}  // namespace

void NmdBlockInput::resize(int rows, int end_count, bool entries) {
  end.assign(end_count, VelocityEnd{});
  jacobian.assign(entries ? 6 * static_cast<std::size_t>(rows) * end_count : 0, 0);
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
  cohesion = 0;
  rolling = 0;
  grain_pair = {};
  memory = nullptr;
  memory_rows = 0;
}

void NmdBlockInput::extend(int rows, int end_count) {
  const int R = this->rows(), E = ends();
  assert(rows >= R && end_count >= E && jacobian.size() == 6 * static_cast<std::size_t>(R) * E);
  // Row r, end e moves from 6 (r E + e) to 6 (r E' + e), never to a lower offset: moved from the
  // last entry down, no entry is overwritten before it is read. Every other slot is then zeroed.
  jacobian.resize(6 * static_cast<std::size_t>(rows) * end_count, 0);
  end.resize(end_count, VelocityEnd{});  // at() now finds the new layout
  for (int r = R - 1; r >= 0; --r)
    for (int e = E - 1; e >= 0; --e) {
      const Real* from = jacobian.data() + 6 * (static_cast<std::size_t>(r) * E + e);
      std::memmove(at(r, e), from, 6 * sizeof(Real));  // the two may overlap
    }
  for (int r = 0; r < rows; ++r)
    for (int e = r < R ? E : 0; e < end_count; ++e) std::fill(at(r, e), at(r, e) + 6, Real(0));
  auto grow = [&](Vector& x, Real value) {
    x.conservativeResize(rows);
    x.tail(rows - R).setConstant(value);
  };
  grow(C, 0);
  grow(known, 0);
  grow(target, 0);
  grow(lower, -kInfinity);
  grow(upper, kInfinity);
  compliance.conservativeResize(rows, rows);
  compliance.rightCols(rows - R).setZero();
  compliance.bottomRows(rows - R).setZero();
  for (int r = R; r < rows; ++r) level[r] = RowLevel::position;
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
  impulse.clear();
  normal_coupling.clear();
  inverse_diagonal.clear();
  sigma_block.clear();
  inverse.clear();
  grain_pairs.clear();
}

void NmdSystem::grow(Index block_count, Index end_count, Index rows, Index entries, Index matrix_entries) {
  blocks.resize(blocks.size() + block_count);
  block_ends.resize(block_ends.size() + end_count);
  for (std::vector<Real>* row_values : {&rhs, &lower, &upper, &sigma, &impulse, &normal_coupling, &inverse_diagonal})
    row_values->resize(row_values->size() + rows);
  jacobian_offset.resize(jacobian_offset.size() + rows);
  row_block.resize(row_block.size() + rows);
  jacobian.resize(jacobian.size() + entries);
  weighted.resize(weighted.size() + entries);
  inverse.resize(inverse.size() + matrix_entries);
  sigma_block.resize(sigma_block.size() + matrix_entries);
}

void NmdSystem::add(const NmdBlockInput& in, const VelocitySpace& space, Real h, const NmdSettings& settings) {
  const int R = in.rows();
  Index stride = 0;  // Jacobian entries per row: the sizes of the ends (the world's end keeps none; a grain pair none)
  if (in.kind != NmdBlockKind::grain_pair)
    for (const VelocityEnd& e : in.end) stride += e.size;
  NmdSlot slot;
  slot.block = static_cast<Index>(blocks.size());
  slot.first_row = row_count();
  slot.first_end = static_cast<Index>(block_ends.size());
  slot.first_entry = static_cast<Index>(jacobian.size());
  // Equality blocks keep the inverse of their R x R matrix; a contact block with turning rows the
  // inverse of its 3 x 3 turning block.
  const bool turning_block = in.kind == NmdBlockKind::contact && R == 6;
  slot.matrix = in.kind == NmdBlockKind::equality || turning_block ? static_cast<Index>(inverse.size()) : -1;
  if (in.kind == NmdBlockKind::grain_pair) {
    slot.grain_pair = static_cast<Index>(grain_pairs.size());
    grain_pairs.emplace_back();
  }
  grow(1, in.ends(), R, R * stride, in.kind == NmdBlockKind::equality ? R * R : turning_block ? 9 : 0);
  fill(slot, in, space, h, settings);
}

void NmdSystem::fill(const NmdSlot& slot, const NmdBlockInput& in, const VelocitySpace& space, Real h,
                     const NmdSettings& settings) {
  const int R = in.rows();
  const bool contact_block = in.kind == NmdBlockKind::contact || in.kind == NmdBlockKind::grain_pair;
  NmdBlock block;
  block.kind = in.kind;
  block.rows = R;
  block.ends = in.ends();
  block.first_row = slot.first_row;
  block.first_end = slot.first_end;
  for (int e = 0; e < in.ends(); ++e) {
    block_ends[slot.first_end + e] = in.end[e];
    block_ends[slot.first_end + e].moves = space.moves(in.end[e]);
  }
  block.memory = in.memory;
  block.memory_rows = in.memory_rows;

  // SPOOK coefficients with d = tau / h, tau at least settings.stabilization steps.
  const Real d = std::max(in.damping_time / h, settings.stabilization);
  const Real a = 4 / (h * (1 + 4 * d)), b = 1 / (1 + 4 * d), spook = 4 / (h * h * (1 + 4 * d));
  // S per row: position rows eps 4 / (h^2 (1 + 4d)); velocity and friction rows eps / h.
  NmdBlockInput::Vector scale(R);
  for (int r = 0; r < R; ++r) scale[r] = in.level[r] == RowLevel::position ? spook : 1 / h;

  // A = G W G^T over the block (S is added below), and the rows' rates G v at the step's start.
  NmdBlockInput::Matrix A = NmdBlockInput::Matrix::Zero(R, R);
  NmdBlockInput::Vector start_rate(R);
  if (in.kind == NmdBlockKind::grain_pair) {
    for (int r = 0; r < R; ++r) {
      jacobian_offset[slot.first_row + r] = slot.first_entry;  // no entries
      row_block[slot.first_row + r] = slot.block;
    }
    block.grain_pair = slot.grain_pair;
    GrainPairRows& g = grain_pairs[slot.grain_pair] = in.grain_pair;
    for (int side = 0; side < 2; ++side) {
      g.inv_mass[side] = space.point_inverse_mass(in.end[side].dof);
      g.inv_inertia[side] = space.point_inverse_mass(in.end[2 + side].dof);
    }
    grain_pair_system(g, in.end.data(), space.v, A, start_rate);
  } else {
    const Index first_entry = slot.first_entry;
    Index entry = first_entry;
    for (int r = 0; r < R; ++r) {
      jacobian_offset[slot.first_row + r] = entry;
      row_block[slot.first_row + r] = slot.block;
      for (int e = 0; e < in.ends(); ++e) {
        const int size = in.end[e].size;  // the world's end keeps no entries
        if (size == 0) continue;
        const Real* J = in.at(r, e);
        Real W[6];
        space.apply_inverse_mass(in.end[e], J, W);
        std::copy(J, J + size, jacobian.begin() + entry);
        std::copy(W, W + size, weighted.begin() + entry);
        entry += size;
      }
    }
    const Index stride = (entry - first_entry) / R;
    for (int r = 0; r < R; ++r)
      for (int s = 0; s < R; ++s) {
        Real value = 0;
        for (Index k = 0; k < stride; ++k)
          value += jacobian[first_entry + r * stride + k] * weighted[first_entry + s * stride + k];
        A(r, s) = value;
      }
    for (int r = 0; r < R; ++r) start_rate[r] = rate(block, block.first_row + r, space.v);
  }
  // An impact (a contact closing faster than the restitution threshold within this step) is a
  // rigid collision with Newton's restitution law: its normal row drops the contact compliance,
  // which would otherwise absorb the rebound within the damping time.
  NmdBlockInput::Matrix compliance = in.damper_rate > 0 ? NmdBlockInput::Matrix(A / in.damper_rate) : in.compliance;
  bool impact = false;
  if (contact_block && in.restitution > 0) {
    const Real closing = start_rate[0] + in.known[0];
    impact = closing < -settings.restitution_threshold && in.C[0] + h * closing <= 0;
  }
  if (impact) compliance(0, 0) = 0;
  for (int r = 0; r < R; ++r)
    for (int s = 0; s < R; ++s) A(r, s) += 0.5 * (scale[r] + scale[s]) * compliance(r, s);

  for (int r = 0; r < R; ++r) {
    // dC/dt at the step's start, with the part from ends outside the velocity vector.
    const Real rate = start_rate[r] + in.known[r];
    Real target = 0;  // what dC/dt + (S l)_r should be after the solve
    switch (in.level[r]) {
      case RowLevel::position: target = -a * in.C[r] + b * rate; break;
      case RowLevel::velocity: target = in.target[r]; break;
      case RowLevel::friction: target = 0; break;
    }
    if (contact_block && r == 0) {
      // A speculative contact may close its gap within the step, no further; an impact faster
      // than the threshold that closes the gap this step leaves at e times its speed.
      // An adhesive contact (lower bound below 0) is held by its spring instead.
      if (in.C[r] > 0 && in.lower[r] >= 0) target = -in.C[r] / h;
      if (impact) target = std::max(target, -in.restitution * rate);
    }
    const Index row = slot.first_row + r;
    rhs[row] = target - in.known[r];
    sigma[row] = scale[r] * compliance(r, r);
    normal_coupling[row] =
        contact_block && r > 0 ? A(r, 0) - 0.5 * (scale[r] + scale[0]) * compliance(r, 0) : 0;
    // A contact's friction rows share the larger of their diagonals, and its turning rows theirs.
    Real D = A(r, r);
    if (contact_block && r > 0)
      D = r < 3 ? std::max(A(1, 1), A(2, 2)) : std::max({A(3, 3), A(4, 4), A(5, 5)});
    inverse_diagonal[row] = D > 0 ? 1 / D : 0;
    lower[row] = in.lower[r] * h;
    upper[row] = in.upper[r] * h;
    impulse[row] = 0;
  }
  if (contact_block && R >= 3) {
    Real slip2 = 0;
    for (int r = 1; r < 3; ++r) {
      const Real rate = start_rate[r] + in.known[r];
      slip2 += rate * rate;
    }
    block.friction = slip2 > settings.sliding_speed * settings.sliding_speed ? in.dynamic_friction : in.static_friction;
    block.cohesion = in.cohesion * h;
    block.rolling = in.rolling;
  }
  if (in.kind == NmdBlockKind::contact && R == 6) {
    // The turning rows' own block of G W G^T (they carry no compliance): against a rigid body its
    // world inverse inertia couples them, and a step scaled by the largest diagonal alone may
    // overshoot; its inverse makes each sweep's turning update exact for the block. A grain side
    // turns, so the block is at least I_grain^-1 times the identity: positive definite.
    block.matrix = slot.matrix;
    const Mat3 inv = A.block<3, 3>(3, 3).inverse();
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) inverse[slot.matrix + 3 * r + c] = inv(r, c);
  }
  if (in.kind == NmdBlockKind::equality) {
    block.matrix = slot.matrix;
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
        inverse[slot.matrix + r * R + s] = inv(r, s);
        sigma_block[slot.matrix + r * R + s] = 0.5 * (scale[r] + scale[s]) * compliance(r, s);
      }
  }
  blocks[slot.block] = block;
}

}  // namespace moreau
