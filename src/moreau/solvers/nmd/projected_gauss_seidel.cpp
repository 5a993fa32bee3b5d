#include "moreau/solvers/nmd/projected_gauss_seidel.hpp"

#include <algorithm>
#include <cmath>

#include <omp.h>

namespace moreau {

namespace {

// Row i's Jacobian and W J^T and the velocities they act on.
struct RowAccess {
  NmdSystem& s;
  std::vector<Real>& v;

  Real rate(const NmdBlock& b, Index row) const { return s.rate(b, row, v); }
  void apply(const NmdBlock& b, Index row, Real dl) const {
    if (dl == 0) return;
    const Real* W = s.weighted.data() + s.jacobian_offset[row];
    const VelocityEnd* end = s.ends_of(b);
    for (int e = 0; e < b.ends; ++e) {
      if (end[e].moves)  // an immovable end's W is 0: skipping it leaves it untouched for other threads
        for (int c = 0; c < end[e].size; ++c) v[end[e].dof + c] += W[c] * dl;
      W += end[e].size;
    }
  }
  // r_i = G_i v + S_ii l_i - q_i (rows of bounded and contact blocks have a diagonal S).
  Real residual(const NmdBlock& b, Index row) const { return rate(b, row) + s.sigma[row] * s.impulse[row] - s.rhs[row]; }
};

// The friction impulse (l1, l2) of a contact projected onto its bound mu (l_n + F h), F h a
// cohesive bond's share (0 without one).
void project_friction(Real& l1, Real& l2, Real normal, const NmdBlock& b, FrictionBound bound) {
  const Real limit = b.friction * std::max(normal + b.cohesion, Real(0));
  if (bound == FrictionBound::box) {
    l1 = std::clamp(l1, -limit, limit);
    l2 = std::clamp(l2, -limit, limit);
    return;
  }
  const Real length = std::sqrt(l1 * l1 + l2 * l2);  // impulses are far from overflow; std::hypot costs 5x
  if (length <= limit) return;
  const Real factor = limit / length;
  l1 *= factor;
  l2 *= factor;
}

void solve_equality(const RowAccess& a, const NmdBlock& b, Real omega) {
  const int R = b.rows;
  Real r[NmdBlockInput::kMaxRows], dl[NmdBlockInput::kMaxRows];
  const Real* S = a.s.sigma_block.data() + b.matrix;
  for (int i = 0; i < R; ++i) {
    Real value = a.rate(b, b.first_row + i) - a.s.rhs[b.first_row + i];
    for (int j = 0; j < R; ++j) value += S[i * R + j] * a.s.impulse[b.first_row + j];
    r[i] = value;
  }
  const Real* inv = a.s.inverse.data() + b.matrix;
  for (int i = 0; i < R; ++i) {
    Real value = 0;
    for (int j = 0; j < R; ++j) value -= inv[i * R + j] * r[j];
    dl[i] = omega * value;
  }
  for (int i = 0; i < R; ++i) {
    a.s.impulse[b.first_row + i] += dl[i];
    a.apply(b, b.first_row + i, dl[i]);
  }
}

void solve_bounded_row(const RowAccess& a, const NmdBlock& b, Index row, Real omega) {
  const Real inverse_D = a.s.inverse_diagonal[row];
  if (inverse_D <= 0) return;
  Real& l = a.s.impulse[row];
  const Real next = std::clamp(l - omega * a.residual(b, row) * inverse_D, a.s.lower[row], a.s.upper[row]);
  a.apply(b, row, next - l);
  l = next;
}

// A grain contact's three turning rows (rows 3 to 5, turning_contact_rows.hpp) after its normal
// and friction rows, at the velocities those left: the three together, l <- l - omega (G W G^T)^-1
// r with the inverse of their own 3 x 3 block (nmd_system.cpp: against a rigid body its inverse
// inertia couples them), projected onto the ball |l| <= mu_r R* (l_n + F h) of the rolling
// resistance. The rates are read in one pass over the ends and the impulse changes applied in
// one, as in solve_contact.
void solve_turning(const RowAccess& a, const NmdBlock& b, Real omega) {
  NmdSystem& s = a.s;
  const Index first = b.first_row + 3;
  const VelocityEnd* end = s.ends_of(b);
  const Index stride = s.jacobian_offset[first + 1] - s.jacobian_offset[first];
  const Real* J = s.jacobian.data() + s.jacobian_offset[first];
  Real rate[3] = {0, 0, 0};
  for (int e = 0, c0 = 0; e < b.ends; c0 += end[e].size, ++e) {
    if (end[e].size == 0) continue;  // the world
    const Real* v = a.v.data() + end[e].dof;
    for (int k = 0; k < 3; ++k) rate[k] += NmdSystem::end_rate(J + k * stride + c0, v, end[e].size);
  }
  const Real* inv = s.inverse.data() + b.matrix;
  Real residual[3];
  for (int k = 0; k < 3; ++k) residual[k] = rate[k] + s.sigma[first + k] * s.impulse[first + k] - s.rhs[first + k];
  Real l[3], length2 = 0;
  for (int k = 0; k < 3; ++k) {
    l[k] = s.impulse[first + k] -
           omega * (inv[3 * k] * residual[0] + inv[3 * k + 1] * residual[1] + inv[3 * k + 2] * residual[2]);
    length2 += l[k] * l[k];
  }
  const Real limit = b.rolling * std::max(s.impulse[b.first_row] + b.cohesion, Real(0));
  const Real factor = length2 > limit * limit ? limit / std::sqrt(length2) : 1;
  Real d[3];
  for (int k = 0; k < 3; ++k) {
    d[k] = factor * l[k] - s.impulse[first + k];
    s.impulse[first + k] += d[k];
  }
  if (d[0] == 0 && d[1] == 0 && d[2] == 0) return;
  const Real* W = s.weighted.data() + s.jacobian_offset[first];
  for (int e = 0, c0 = 0; e < b.ends; c0 += end[e].size, ++e) {
    if (!end[e].moves) continue;  // an immovable end's W is 0: skipping it leaves it untouched for other threads
    Real* v = a.v.data() + end[e].dof;
    for (int c = 0; c < end[e].size; ++c)
      v[c] += W[c0 + c] * d[0] + W[stride + c0 + c] * d[1] + W[2 * stride + c0 + c] * d[2];
  }
}

// A grain pair's velocities, ends (v_i, v_j, w_i, w_j).
struct GrainPairVelocities {
  Eigen::Map<Vec3> vi, vj, wi, wj;
  GrainPairVelocities(std::vector<Real>& v, const VelocityEnd* end)
      : vi(v.data() + end[0].dof), vj(v.data() + end[1].dof), wi(v.data() + end[2].dof), wj(v.data() + end[3].dof) {}
};

// Impulse changes d on a grain pair's six rows: v += W G^T d (GrainPairRows).
void apply_grain_pair(const GrainPairRows& g, GrainPairVelocities& u, const Real* d) {
  const Vec3 P = d[0] * g.n + d[1] * g.t1 + d[2] * g.t2;
  const Vec3 T = d[2] * g.t1 - d[1] * g.t2;
  const Vec3 L = d[3] * g.t1 + d[4] * g.t2 + d[5] * g.n;
  u.vi += g.inv_mass[0] * P;
  u.vj -= g.inv_mass[1] * P;
  u.wi += g.inv_inertia[0] * (g.arm[0] * T + L);
  u.wj += g.inv_inertia[1] * (g.arm[1] * T - L);
}

// A grain pair: the same Gauss-Seidel update as solve_contact and solve_turning, with the rows in
// closed form. The normal row's change leaves the friction rates alone (t . n = 0: no coupling);
// the turning rows are solved at the velocities the friction left.
void solve_grain_pair(const RowAccess& a, const NmdBlock& b, Real omega, FrictionBound bound) {
  NmdSystem& s = a.s;
  const GrainPairRows& g = s.grain_pairs[b.grain_pair];
  GrainPairVelocities u(a.v, s.ends_of(b));
  const Index n = b.first_row;
  Real* l = s.impulse.data() + n;
  Real d[6] = {0, 0, 0, 0, 0, 0};
  const Vec3 dv = u.vi - u.vj, lever = g.arm[0] * u.wi + g.arm[1] * u.wj;
  if (s.inverse_diagonal[n] > 0) {
    const Real rate = g.n.dot(dv);
    const Real next =
        std::clamp(l[0] - omega * (rate + s.sigma[n] * l[0] - s.rhs[n]) * s.inverse_diagonal[n], s.lower[n], s.upper[n]);
    d[0] = next - l[0];
    l[0] = next;
  }
  const Real inverse_friction = s.inverse_diagonal[n + 1];
  if (inverse_friction > 0) {
    const Real r1 = g.t1.dot(dv) - g.t2.dot(lever) + s.sigma[n + 1] * l[1] - s.rhs[n + 1];
    const Real r2 = g.t2.dot(dv) + g.t1.dot(lever) + s.sigma[n + 2] * l[2] - s.rhs[n + 2];
    Real l1 = l[1] - omega * r1 * inverse_friction, l2 = l[2] - omega * r2 * inverse_friction;
    project_friction(l1, l2, l[0], b, bound);
    d[1] = l1 - l[1];
    d[2] = l2 - l[2];
    l[1] = l1;
    l[2] = l2;
  }
  apply_grain_pair(g, u, d);
  const Real inverse_turning = s.inverse_diagonal[n + 3];
  if (inverse_turning <= 0) return;
  const Vec3 turn = u.wi - u.wj;
  const Vec3 next = Vec3(l[3], l[4], l[5]) - omega * inverse_turning *
                                                 (Vec3(g.t1.dot(turn), g.t2.dot(turn), g.n.dot(turn)) +
                                                  Vec3(s.sigma[n + 3] * l[3] - s.rhs[n + 3], s.sigma[n + 4] * l[4] - s.rhs[n + 4],
                                                       s.sigma[n + 5] * l[5] - s.rhs[n + 5]));
  const Real limit = b.rolling * std::max(l[0] + b.cohesion, Real(0));
  const Real length2 = next.squaredNorm();
  const Vec3 bounded = length2 > limit * limit ? Vec3(next * (limit / std::sqrt(length2))) : next;
  const Real turning[6] = {0, 0, 0, bounded[0] - l[3], bounded[1] - l[4], bounded[2] - l[5]};
  l[3] = bounded[0];
  l[4] = bounded[1];
  l[5] = bounded[2];
  apply_grain_pair(g, u, turning);
}

// A contact point: the normal row, then its two friction rows bounded by mu times the new normal
// impulse (solved together, by Jacobi between them, with the larger of their diagonals). It is
// the Gauss-Seidel update of the rows one after the other, fused: the three rates are read in one
// pass over the ends, the friction rates take the normal update through their coupling
// G_t W G_n^T (v changes by W G_n^T dl_n, so G_t v by G_t W G_n^T dl_n), and v takes the three
// impulse changes in one pass.
void solve_contact(const RowAccess& a, const NmdBlock& b, Real omega, FrictionBound bound) {
  const Index n = b.first_row, t1 = n + 1, t2 = n + 2;
  if (b.rows == 1) return solve_bounded_row(a, b, n, omega);  // frictionless (fluid particles on walls)
  NmdSystem& s = a.s;
  const VelocityEnd* end = s.ends_of(b);
  const Index stride = s.jacobian_offset[t1] - s.jacobian_offset[n];
  const Real* J = s.jacobian.data() + s.jacobian_offset[n];
  Real rate_n = 0, rate_1 = 0, rate_2 = 0;
  for (int e = 0, c0 = 0; e < b.ends; c0 += end[e].size, ++e) {
    if (end[e].size == 0) continue;  // the world
    const Real* v = a.v.data() + end[e].dof;
    rate_n += NmdSystem::end_rate(J + c0, v, end[e].size);
    rate_1 += NmdSystem::end_rate(J + stride + c0, v, end[e].size);
    rate_2 += NmdSystem::end_rate(J + 2 * stride + c0, v, end[e].size);
  }
  Real dn = 0;
  if (s.inverse_diagonal[n] > 0) {
    const Real next = std::clamp(
        s.impulse[n] - omega * (rate_n + s.sigma[n] * s.impulse[n] - s.rhs[n]) * s.inverse_diagonal[n], s.lower[n],
        s.upper[n]);
    dn = next - s.impulse[n];
    s.impulse[n] = next;
  }
  Real d1 = 0, d2 = 0;
  const Real inverse_D = s.inverse_diagonal[t1];  // 1 / max(D_t1, D_t2)
  if (inverse_D > 0) {
    const Real r1 = rate_1 + s.normal_coupling[t1] * dn + s.sigma[t1] * s.impulse[t1] - s.rhs[t1];
    const Real r2 = rate_2 + s.normal_coupling[t2] * dn + s.sigma[t2] * s.impulse[t2] - s.rhs[t2];
    Real l1 = s.impulse[t1] - omega * r1 * inverse_D, l2 = s.impulse[t2] - omega * r2 * inverse_D;
    project_friction(l1, l2, s.impulse[n], b, bound);
    d1 = l1 - s.impulse[t1];
    d2 = l2 - s.impulse[t2];
    s.impulse[t1] = l1;
    s.impulse[t2] = l2;
  }
  if (dn != 0 || d1 != 0 || d2 != 0) {
    const Real* W = s.weighted.data() + s.jacobian_offset[n];
    for (int e = 0, c0 = 0; e < b.ends; c0 += end[e].size, ++e) {
      if (!end[e].moves) continue;  // an immovable end's W is 0: skipping it leaves it untouched for other threads
      Real* v = a.v.data() + end[e].dof;
      for (int c = 0; c < end[e].size; ++c)
        v[c] += W[c0 + c] * dn + W[stride + c0 + c] * d1 + W[2 * stride + c0 + c] * d2;
    }
  }
  if (b.rows == 6) solve_turning(a, b, omega);
}

}  // namespace

void warm_start(NmdSystem& system, VelocitySpace& space, const NmdSettings& settings, Real h) {
  const RowAccess a{system, space.v};
  for (const NmdBlock& b : system.blocks) {
    if (!settings.warm_start || b.memory == nullptr) continue;
    for (int i = 0; i < b.memory_rows; ++i) {
      const Index row = b.first_row + i;
      system.impulse[row] = std::clamp(b.memory[i] / h, system.lower[row], system.upper[row]);
    }
    if (b.kind == NmdBlockKind::contact && b.memory_rows == 3)
      project_friction(system.impulse[b.first_row + 1], system.impulse[b.first_row + 2], system.impulse[b.first_row], b,
                       settings.friction);
    if (b.kind == NmdBlockKind::grain_pair) {
      GrainPairVelocities u(space.v, system.ends_of(b));
      Real d[6] = {0, 0, 0, 0, 0, 0};
      for (int i = 0; i < b.memory_rows; ++i) d[i] = system.impulse[b.first_row + i];
      apply_grain_pair(system.grain_pairs[b.grain_pair], u, d);
      continue;
    }
    for (int i = 0; i < b.memory_rows; ++i) a.apply(b, b.first_row + i, system.impulse[b.first_row + i]);
  }
}

namespace {

void solve_block(const RowAccess& a, const NmdBlock& b, const NmdSettings& settings) {
  const Real omega = settings.over_relaxation;
  switch (b.kind) {
    case NmdBlockKind::equality: solve_equality(a, b, omega); break;
    case NmdBlockKind::bounded:
      for (int i = 0; i < b.rows; ++i) solve_bounded_row(a, b, b.first_row + i, omega);
      break;
    case NmdBlockKind::contact: solve_contact(a, b, omega, settings.friction); break;
    case NmdBlockKind::grain_pair: solve_grain_pair(a, b, omega, settings.friction); break;
  }
}

// The blocks of tasks [first, last) in schedule order; returns the largest impulse change when
// kTrackChange (the convergence test of gauss_seidel_sweep), 0 otherwise.
template <bool kTrackChange>
Real solve_tasks(const RowAccess& a, const SweepSchedule& schedule, Index first, Index last,
                 const NmdSettings& settings, bool equality_blocks, bool bounded_blocks) {
  Real largest = 0;
  for (Index t = first; t < last; ++t)
    for (Index i = schedule.task_block[t]; i < schedule.task_end[t]; ++i) {
      const NmdBlock& b = a.s.blocks[i];
      if ((b.kind == NmdBlockKind::equality && !equality_blocks) || (b.kind == NmdBlockKind::bounded && !bounded_blocks))
        continue;
      if constexpr (kTrackChange) {
        Real before[NmdBlockInput::kMaxRows];
        for (int r = 0; r < b.rows; ++r) before[r] = a.s.impulse[b.first_row + r];
        solve_block(a, b, settings);
        for (int r = 0; r < b.rows; ++r)
          largest = std::max(largest, std::abs(a.s.impulse[b.first_row + r] - before[r]));
      } else {
        solve_block(a, b, settings);
      }
    }
  return largest;
}

// One sweep, level by level (sweep_schedule.hpp), by every thread of the enclosing parallel
// region: each level's tasks are split between the threads, and the loop's implicit barrier
// closes the level. Returns this thread's largest change.
template <bool kTrackChange>
Real shared_sweep(const RowAccess& a, const SweepSchedule& schedule, const NmdSettings& settings, bool equality_blocks,
                  bool bounded_blocks) {
  Real largest = 0;
  for (Index level = 0; level < schedule.levels(); ++level) {
#pragma omp for schedule(static)
    for (Index t = schedule.level_first[level]; t < schedule.level_first[level + 1]; ++t)
      largest = std::max(largest, solve_tasks<kTrackChange>(a, schedule, t, t + 1, settings, equality_blocks, bounded_blocks));
  }
  return largest;
}

}  // namespace

// Threads for a sweep: one unless the levels hold 64 tasks on average. Measured on two cores:
// 1000 boxes on the ground (111 tasks a level) solve 1.71x faster on two threads; the 210-box
// pyramid (5 a level: its contacts chain along the rows) and a 2462-tetrahedron soft body (45 a
// level) gain nothing, the barrier closing each level costing what the second thread saves.
int sweep_threads(const SweepSchedule& schedule, int threads) {
  constexpr Index kTasksPerThread = 64;
  return schedule.tasks() >= kTasksPerThread * std::max<Index>(1, schedule.levels()) ? std::max(1, threads) : 1;
}

Real gauss_seidel_sweep(NmdSystem& system, VelocitySpace& space, const NmdSettings& settings,
                        const SweepSchedule& schedule, int threads, bool equality_blocks, bool bounded_blocks) {
  const RowAccess a{system, space.v};
  const int team = sweep_threads(schedule, threads);
  if (team == 1) return solve_tasks<true>(a, schedule, 0, schedule.tasks(), settings, equality_blocks, bounded_blocks);
  std::vector<Real> largest(team, 0);
#pragma omp parallel num_threads(team)
  largest[omp_get_thread_num()] = shared_sweep<true>(a, schedule, settings, equality_blocks, bounded_blocks);
  return *std::max_element(largest.begin(), largest.end());
}

void projected_gauss_seidel(NmdSystem& system, VelocitySpace& space, const NmdSettings& settings,
                            const SweepSchedule& schedule, int threads) {
  const RowAccess a{system, space.v};
  const int team = sweep_threads(schedule, threads);
  if (team == 1) {
    for (int sweep = 0; sweep < settings.iterations; ++sweep)
      solve_tasks<false>(a, schedule, 0, schedule.tasks(), settings, true, true);
    return;
  }
#pragma omp parallel num_threads(team)
  for (int sweep = 0; sweep < settings.iterations; ++sweep) shared_sweep<false>(a, schedule, settings, true, true);
}

void store_impulses(const NmdSystem& system, Real h) {
  for (const NmdBlock& b : system.blocks)
    for (int i = 0; i < b.memory_rows; ++i) b.memory[i] = system.impulse[b.first_row + i] * h;
}

}  // namespace moreau
