#include "moreau/fluids/phase_drift.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "moreau/fluids/fluid_scratch.hpp"
#include "moreau/fluids/fluid_state.hpp"
#include "moreau/model/model.hpp"

namespace moreau {

namespace {

// Schiller & Naumann's drag coefficient of a sphere at Reynolds number re (> 0).
Real sphere_drag_coefficient(Real re) {
  if (re >= 1000) return 0.44;
  return 24 / re * (1 + 0.15 * std::pow(re, 0.687));
}

// A uniform draw in [0, 1) from the step and an ordered pair of particle ids (splitmix64's
// finaliser), the same whichever thread asks.
Real pair_draw(long step, Index a, Index b) {
  std::uint64_t z = static_cast<std::uint64_t>(step) * 0x9E3779B97F4A7C15ull;
  z ^= static_cast<std::uint64_t>(a) * 0xBF58476D1CE4E5B9ull + static_cast<std::uint64_t>(b);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  z ^= z >> 31;
  return static_cast<Real>(z >> 11) * 0x1.0p-53;
}

constexpr Index kNone = -1;

}  // namespace

Real terminal_drift_speed(Real d, Real rho_drop, Real rho_liquid, Real mu, Real g) {
  const Real weight = std::abs(rho_drop - rho_liquid) * g * kPi * d * d * d / 6;  // N, buoyant weight
  if (weight <= 0) return 0;
  const Real drag_scale = rho_liquid * kPi * d * d / 8;  // drag = C_d drag_scale u^2
  // The drag C_d(Re(u)) u^2 grows with u, so the balance has one root: bisect on u.
  Real lo = 0, hi = std::sqrt(weight / (0.44 * drag_scale)) * 2 + 1e-12;
  if (mu > 0) hi = std::max(hi, weight / (3 * kPi * mu * d) * 2);  // above Stokes' speed
  for (int k = 0; k < 200; ++k) {
    const Real u = 0.5 * (lo + hi);
    const Real cd = mu > 0 ? sphere_drag_coefficient(rho_liquid * u * d / mu) : 0.44;
    (cd * drag_scale * u * u > weight ? hi : lo) = u;
  }
  return 0.5 * (lo + hi);
}

void set_up_phase_drift(FluidModel& fm, Real g) {
  const Index phases = static_cast<Index>(fm.phases.size());
  const Real d = std::cbrt(6 * fm.particle_volume / kPi);  // the sphere of one particle's volume
  fm.drift_speed.assign(static_cast<std::size_t>(phases * phases), 0);
  for (Index a = 0; a < phases; ++a)
    for (Index b = 0; b < phases; ++b) {
      const FluidPhase& drop = fm.phases[a];
      const FluidPhase& liquid = fm.phases[b];
      if (a == b || drop.gas || liquid.gas) continue;
      fm.drift_speed[a * phases + b] =
          terminal_drift_speed(d, drop.rest_density, liquid.rest_density, liquid.viscosity * liquid.rest_density, g);
    }
}

Index drift_phases(const Model& model, FluidState& fluid, FluidScratch& scratch, long step, int threads) {
  const FluidModel& fm = model.fluid;
  const Real g = model.settings.gravity.norm();
  if (!fm.phase_drift || fluid.list_builds == 0 || g == 0) return 0;
  const Real dt = model.settings.dt;
  const Vec3 up = -model.settings.gravity / g;
  const Index n = fluid.count, phases = static_cast<Index>(fm.phases.size());
  const Real reach2 = 9 * fm.particle_radius * fm.particle_radius;  // pairs within 1.5 spacings
  const Real least_rise = 0.5 * fm.particle_radius;                 // a pair side by side does not trade
  auto movable = [&](Index i) { return fluid.inv_mass[i] > 0 && !fm.phases[fluid.phase[i]].gas; };

  // 1. Each movable particle proposes the heavier particle of another liquid highest above it,
  //    and counts its neighbours of its own liquid and of others (to say which is dispersed).
  if (scratch.drift_proposal.size() < static_cast<std::size_t>(n)) {  // once a run (the fluid's capacity)
    const std::size_t capacity = std::max<std::size_t>(n, fm.capacity);
    scratch.drift_proposal.resize(capacity);
    scratch.drift_partner.resize(capacity);
    scratch.drift_rise.resize(capacity);
    scratch.drift_minority.resize(capacity);
  }
  Index* proposal = scratch.drift_proposal.data();
  Index* partner = scratch.drift_partner.data();
  Real* rise = scratch.drift_rise.data();
  char* minority = scratch.drift_minority.data();  // fewer of i's neighbours are of its own liquid than of others
#pragma omp parallel for schedule(static) num_threads(threads)
  for (Index i = 0; i < n; ++i) {
    proposal[i] = kNone;
    if (!movable(i)) continue;
    const Vec3 xi = fluid.position[i];
    Index best = kNone, own = 0, other = 0;
    Real best_rise = least_rise;
    const Index* row = fluid.fluid_neighbors.row(i);
    for (Index k = 0; k < fluid.fluid_neighbors.count[i]; ++k) {
      const Index j = row[k];
      const Vec3 r = fluid.position[j] - xi;
      const Real r2 = r.squaredNorm();
      if (r2 < fm.kernel.h2) ++(fluid.phase[j] == fluid.phase[i] ? own : other);
      if (fluid.phase[j] == fluid.phase[i] || fluid.mass[j] <= fluid.mass[i] || !movable(j)) continue;
      const Real s = r.dot(up);
      if (r2 >= reach2 || s < best_rise) continue;
      if (s == best_rise && best != kNone && fluid.id[j] > fluid.id[best]) continue;
      best = j;
      best_rise = s;
    }
    proposal[i] = best;
    rise[i] = best_rise;
    minority[i] = own < other;
  }

  // 2. Each particle proposed to (and not proposing itself) accepts the proposal from the
  //    particle furthest below it, and the pair trades with probability u dt / s.
#pragma omp parallel for schedule(static) num_threads(threads)
  for (Index j = 0; j < n; ++j) {
    partner[j] = kNone;
    if (proposal[j] != kNone) continue;
    Index chosen = kNone;
    const Index* row = fluid.fluid_neighbors.row(j);
    for (Index k = 0; k < fluid.fluid_neighbors.count[j]; ++k) {
      const Index i = row[k];
      if (proposal[i] != j) continue;
      if (chosen == kNone || rise[i] > rise[chosen] || (rise[i] == rise[chosen] && fluid.id[i] < fluid.id[chosen]))
        chosen = i;
    }
    if (chosen == kNone) continue;
    const Index light = fluid.phase[chosen], heavy = fluid.phase[j];
    const Real u = minority[chosen] ? fm.drift_speed[light * phases + heavy] : fm.drift_speed[heavy * phases + light];
    if (pair_draw(step, fluid.id[chosen], fluid.id[j]) < u * dt / rise[chosen]) partner[j] = chosen;
  }

  // 3. The trades: disjoint pairs, so their order does not matter.
  Index trades = 0;
  for (Index j = 0; j < n; ++j) {
    if (partner[j] == kNone) continue;
    std::swap(fluid.position[j], fluid.position[partner[j]]);
    std::swap(fluid.pressure[j], fluid.pressure[partner[j]]);
    ++trades;
  }
  if (trades > 0) fluid.lists_stale = true;
  return trades;
}

}  // namespace moreau
