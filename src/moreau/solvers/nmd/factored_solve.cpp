#include <algorithm>
#include <cmath>

#include "moreau/solvers/nmd/projected_gauss_seidel.hpp"
#include "moreau/solvers/nmd/solve_methods.hpp"

namespace moreau {

namespace {

enum class RowState : char { free, at_lower, at_upper };

// The rows the method factors: equality blocks, and for direct the bounded blocks too.
std::vector<Index> factored_rows(const NmdSystem& system, NmdMethod method) {
  std::vector<Index> rows;
  for (const NmdBlock& b : system.blocks)
    if (b.kind == NmdBlockKind::equality || (method == NmdMethod::direct && b.kind == NmdBlockKind::bounded))
      for (int r = 0; r < b.rows; ++r) rows.push_back(b.first_row + r);
  return rows;
}

// The factored rows' impulses l (in/out) for A l = b within [lower, upper] by block principal
// pivoting; rows with infinite bounds never clamp, so without bounds this is one solve.
bool solve_bounded(SchurComplement& schur, const VectorX& b, const VectorX& lower, const VectorX& upper, VectorX& l,
                   std::vector<RowState>& state, int passes) {
  const Index m = static_cast<Index>(b.size());
  const Real tolerance = 1e-12 * std::max(Real(1), b.cwiseAbs().maxCoeff());
  std::vector<char> clamped(m);
  for (int pass = 0; pass < passes; ++pass) {
    VectorX fixed = VectorX::Zero(m);
    for (Index i = 0; i < m; ++i) {
      clamped[i] = state[i] != RowState::free;
      if (state[i] == RowState::at_lower) fixed[i] = lower[i];
      if (state[i] == RowState::at_upper) fixed[i] = upper[i];
    }
    if (!schur.factorize(clamped)) return false;
    const VectorX coupling = schur.product(fixed);
    VectorX rhs(m);
    for (Index i = 0; i < m; ++i) rhs[i] = clamped[i] ? fixed[i] : b[i] - coupling[i];
    l = schur.solve(rhs);
    const VectorX w = schur.product(l) - b;
    bool changed = false;
    for (Index i = 0; i < m; ++i) {
      RowState next = state[i];
      if (state[i] == RowState::free) {
        if (l[i] < lower[i]) next = RowState::at_lower;
        else if (l[i] > upper[i]) next = RowState::at_upper;
      } else if ((state[i] == RowState::at_lower && w[i] < -tolerance) ||
                 (state[i] == RowState::at_upper && w[i] > tolerance)) {
        next = RowState::free;
      }
      changed |= next != state[i];
      state[i] = next;
    }
    if (!changed) break;
  }
  l = l.cwiseMax(lower).cwiseMin(upper);
  return true;
}

}  // namespace

bool solve_factored(NmdSystem& system, VelocitySpace& space, const NmdSettings& settings, SchurComplement& schur,
                    const SweepSchedule& schedule, int threads) {
  const std::vector<Index> rows = factored_rows(system, settings.method);
  const Index m = static_cast<Index>(rows.size());
  if (m == 0) {
    projected_gauss_seidel(system, space, settings, schedule, threads);
    return true;
  }
  const bool others = m < system.row_count();
  const bool bounded = settings.method == NmdMethod::direct;
  schur.build(system, rows, static_cast<Index>(space.v.size()));
  VectorX l(m), q(m), lower(m), upper(m);
  std::vector<RowState> state(m, RowState::free);
  for (Index i = 0; i < m; ++i) {
    l[i] = system.impulse[rows[i]];
    q[i] = system.rhs[rows[i]];
    lower[i] = system.lower[rows[i]];
    upper[i] = system.upper[rows[i]];
    if (l[i] <= lower[i]) state[i] = RowState::at_lower;
    else if (l[i] >= upper[i]) state[i] = RowState::at_upper;
  }
  if (!bounded && !schur.factorize(std::vector<char>(m, 0))) return false;
  // F's rows solved against the velocities the other rows leave; returns the largest change.
  bool regular = true;
  auto solve_rows = [&]() -> Real {
    VectorX next = l;
    if (bounded) {
      // b = q - G v_0 with v_0 = v - W G^T l: A l_new = b  <=>  A (l_new - l) = q - G v - S l.
      const VectorX b = q - schur.rate(space.v) + schur.product(l) - schur.sigma_product(l);
      regular &= solve_bounded(schur, b, lower, upper, next, state, settings.iterations);
    } else {
      next = l - schur.solve(schur.rate(space.v) + schur.sigma_product(l) - q);
    }
    const VectorX dl = next - l;
    schur.apply(dl, space.v);
    l = next;
    return dl.cwiseAbs().maxCoeff();
  };
  for (int round = 0; round < settings.iterations && regular; ++round) {
    const Real factored_change = solve_rows();
    if (!others) break;
    const Real sweep_change = gauss_seidel_sweep(system, space, settings, schedule, threads, false, !bounded);
    if (std::max(factored_change, sweep_change) <= settings.tolerance) break;
  }
  if (others && regular) solve_rows();
  for (Index i = 0; i < m; ++i) system.impulse[rows[i]] = l[i];
  return regular;
}

}  // namespace moreau
