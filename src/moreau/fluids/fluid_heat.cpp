#include "moreau/fluids/fluid_heat.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "moreau/fluids/neighbor_loop.hpp"
#include "moreau/fluids/wall_extrapolation.hpp"
#include "moreau/model/model.hpp"

namespace moreau {
namespace {

constexpr Real kLatticeGradientSum = 17.1;  // S h^2: sum_j 2 V |g| r^2 / (r^2 + eta^2) on the lattice
constexpr Real kStabilityMargin = 0.25;     // of the forward-Euler limit 1 / (alpha S) (fluid_heat.hpp)

/// |r|^2 / (|r|^2 + eta^2) g: Brookshaw's pair weight with eta^2 = 0.01 h^2 (1/m^5).
Real pair_weight(Real d2, Real g, Real eta2) { return d2 / (d2 + eta2) * g; }

/// 2 k_a k_b / (k_a + k_b), 0 if either is 0.
Real pair_conductivity(Real a, Real b) { return a > 0 && b > 0 ? 2 * a * b / (a + b) : 0; }

/// The walls' share of m_i dH_i/dt / V for particle i at temperature T_i: sum over its wall samples
/// of colliders with a temperature of V_b 2 k_i beta (T_i - T_c) g |r|^2 / (|r|^2 + eta^2).
Real wall_heat(const Model& model, const FluidState& fluid, Index i, Real temperature, Real conductivity) {
  const FluidModel& fm = model.fluid;
  const Real eta2 = 0.01 * fm.kernel.h2;
  Real sum = 0;
  for_each_extrapolated_wall_sample(
      model, fluid, i, [](const Collider& c) { return c.temperature.has_value(); },
      [&](Index b, const Collider& c, const Vec3&, Real d2, Real beta) {
        sum += fm.boundary.volume[b] * 2 * conductivity * beta * (temperature - *c.temperature) *
               pair_weight(d2, fm.kernel.gradient_factor(std::sqrt(d2)), eta2);
      });
  return sum;
}

}  // namespace

Real fluid_temperature(const FluidPhase& phase, Real enthalpy) {
  const Real c = phase.specific_heat;
  if (!phase.melting_point) return enthalpy / c;
  const Real solidus = c * *phase.melting_point;
  if (enthalpy < solidus) return enthalpy / c;
  if (enthalpy <= solidus + phase.latent_heat) return *phase.melting_point;
  return (enthalpy - phase.latent_heat) / c;
}

Real fluid_weight_factor(const FluidPhase& phase, Real enthalpy) {
  const Real thermal =
      phase.expansion == 0 ? 0 : phase.expansion * (fluid_temperature(phase, enthalpy) - phase.reference_temperature);
  // A gas in open air: the air of the gas's own density carries the weight m g (ambient_air.hpp).
  return phase.gas ? -thermal : 1 - thermal;
}

Real fluid_liquid_fraction(const FluidPhase& phase, Real enthalpy) {
  if (!phase.melting_point) return 1;
  const Real excess = enthalpy - phase.specific_heat * *phase.melting_point;
  if (excess <= 0) return 0;
  if (excess >= phase.latent_heat) return 1;
  return excess / phase.latent_heat;
}

Real fluid_enthalpy(const FluidPhase& phase, Real temperature) {
  const Real sensible = phase.specific_heat * temperature;
  return phase.melting_point && temperature > *phase.melting_point ? sensible + phase.latent_heat : sensible;
}

Real fluid_particle_viscosity(const FluidPhase& phase, Real enthalpy) {
  if (!phase.melting_point) return phase.viscosity;
  const Real phi = fluid_liquid_fraction(phase, enthalpy);
  if (phi >= 1 || phase.viscosity <= 0) return phase.viscosity;
  return std::pow(phase.solid_viscosity, 1 - phi) * std::pow(phase.viscosity, phi);
}

void set_fluid_particle_state(const FluidPhase& phase, FluidState& fluid, Index i) {
  const Real H = fluid.enthalpy[i];
  fluid.viscosity[i] = fluid_particle_viscosity(phase, H);
  const bool solid = phase.melting_point && fluid_liquid_fraction(phase, H) == 0;
  const bool held = fluid.release_time[i] > 0;  // in its emitter's nozzle: moves on at the emitter's speed
  fluid.inv_mass[i] = solid || held ? 0 : 1 / fluid.mass[i];
  if (solid && !held) fluid.velocity[i].setZero();
}

Real fluid_heat_step_limit(const FluidModel& fm) {
  Real diffusivity = 0;  // m^2/s, the largest k / (rho c)
  for (const FluidPhase& p : fm.phases)
    diffusivity = std::max(diffusivity, p.conductivity / (p.rest_density * p.specific_heat));
  if (diffusivity <= 0) return std::numeric_limits<Real>::infinity();
  return kStabilityMargin * fm.kernel.h2 / (kLatticeGradientSum * diffusivity);
}

void apply_fluid_heat(const Model& model, FluidState& fluid, FluidScratch& scratch, Real dt) {
  const FluidModel& fm = model.fluid;
  if (!fm.thermal) return;
  const CubicSplineKernel& kernel = fm.kernel;
  const Real V = fm.particle_volume, eta2 = 0.01 * kernel.h2;
  const Index n = fluid.count;
  std::vector<Real>& temperature = scratch.temperature;
  std::vector<Real>& heat_change = scratch.heat_change;  // J/kg over the part
  const int parts = std::max(1, static_cast<int>(std::ceil(dt / fm.heat_step_limit - 1e-9)));
  const Real tau = dt / parts;
  for (int part = 0; part < parts; ++part) {
#pragma omp for schedule(static)
    for (Index i = 0; i < n; ++i) temperature[i] = fluid_temperature(fm.phases[fluid.phase[i]], fluid.enthalpy[i]);
#pragma omp for schedule(static)
    for (Index i = 0; i < n; ++i) {
      const Real ki = fm.phases[fluid.phase[i]].conductivity;
      if (ki <= 0) {
        heat_change[i] = 0;
        continue;
      }
      const Real Ti = temperature[i];
      Real sum = 0;  // m_i dH_i/dt / V, W/m^3
      for_each_fluid_neighbor(fluid, kernel, i, [&](Index j, const Vec3& r, Real g) {
        const Real kij = pair_conductivity(ki, fm.phases[fluid.phase[j]].conductivity);
        sum += V * 2 * kij * (Ti - temperature[j]) * pair_weight(r.squaredNorm(), g, eta2);
      });
      sum += wall_heat(model, fluid, i, Ti, ki);
      heat_change[i] = tau * V * sum / fluid.mass[i];
    }
#pragma omp for schedule(static)
    for (Index i = 0; i < n; ++i) fluid.enthalpy[i] += heat_change[i];
  }
#pragma omp for schedule(static)
  for (Index i = 0; i < n; ++i) set_fluid_particle_state(fm.phases[fluid.phase[i]], fluid, i);
}

}  // namespace moreau
