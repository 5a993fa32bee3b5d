#include "moreau/fluids/surface_tension.hpp"

#include <cmath>

#include "moreau/model/model.hpp"

namespace moreau {

namespace {

// a_coh and a_curv (dimensionless; how they were chosen: surface_tension.hpp).
constexpr Real kCohesionWeight = 27.4;
constexpr Real kCurvatureWeight = 0.0548;

// Akinci's cohesion spline C(r) (1/m^3) for support h, with its constants computed once.
struct CohesionSpline {
  Real h, scale, core;  // h; 32 / (pi h^9); h^6 / 64
  explicit CohesionSpline(Real support)
      : h(support), scale(32 / (kPi * std::pow(support, 9))), core(std::pow(support, 6) / 64) {}
  Real operator()(Real r) const {
    if (r <= 0 || r > h) return 0;
    const Real a = (h - r) * (h - r) * (h - r) * r * r * r;
    return 2 * r > h ? scale * a : scale * (2 * a - core);
  }
};

}  // namespace

Real capillary_time_step(Real rest_density, Real spacing, Real surface_tension) {
  return std::sqrt(rest_density * spacing * spacing * spacing / (2 * kPi * surface_tension));
}

void apply_fluid_surface_tension(const Model& model, FluidState& fluid, FluidScratch& scratch, Real dt) {
  const FluidModel& fm = model.fluid;
  bool any = false;
  for (const FluidPhase& p : fm.phases) any |= p.surface_tension > 0;
  if (!any) return;
  const CubicSplineKernel& kernel = fm.kernel;
  const Real h = kernel.h, V = fm.particle_volume;
  // The forces per unit gamma (N/m): a_coh V^2 / h^2 C(r) and a_curv h (n_i - n_j) (see the header).
  const CohesionSpline spline(h);
  const Real cohesion_scale = kCohesionWeight * V * V / (h * h), curvature_scale = kCurvatureWeight * h;
  const Index n = fluid.count;
  std::vector<Vec3>& normal = scratch.correction;  // free between steps
  std::vector<Vec3>& v_new = scratch.reorder_vec;
  auto is_gas = [&](Index i) { return fm.phases[fluid.phase[i]].gas; };
  // Calls pair(j, r, d) for the liquid neighbours j of i (of any liquid phase) with 0 < d = |r| < h,
  // r = x_i - x_j. Counting every liquid makes the forces vanish where two liquids meet with a full
  // neighbourhood: surface tension acts where liquid meets air (or a wall), and the interface
  // between two liquids has its own tension (interfacial_tension.hpp).
  auto for_each_liquid_pair = [&](Index i, auto&& pair) {
    const Index* row = fluid.fluid_neighbors.row(i);
    for (Index k = 0; k < fluid.fluid_neighbors.count[i]; ++k) {
      const Index j = row[k];
      if (is_gas(j)) continue;
      const Vec3 r = fluid.position[i] - fluid.position[j];
      const Real d = r.norm();
      if (d < h && d > 0) pair(j, r, d);
    }
  };

  // n_i = h V sum_j grad W(x_i - x_j) over the liquids: dimensionless, ~0 inside the liquid.
#pragma omp for schedule(static)
  for (Index i = 0; i < n; ++i) {
    Vec3 sum = Vec3::Zero();
    if (!is_gas(i))
      for_each_liquid_pair(i, [&](Index, const Vec3& r, Real d) { sum += kernel.gradient_factor(d) * r; });
    normal[i] = h * V * sum;
  }

  // A pair of particles of different liquids takes the mean of their gammas, 2 / (rho_i / rho0_i +
  // rho_j / rho0_j) as its symmetrisation: its forces stay equal and opposite, and two liquids of
  // equal gamma pull on each other as on themselves.
#pragma omp for schedule(static)
  for (Index i = 0; i < n; ++i) {
    const Index own = fluid.phase[i];
    const FluidPhase& phase = fm.phases[own];
    v_new[i] = fluid.velocity[i];
    if (phase.gas || fluid.inv_mass[i] == 0) continue;  // a gas, or a solid or held particle
    const Real gamma = phase.surface_tension, rho0 = phase.rest_density;
    Vec3 same = Vec3::Zero(), mixed = Vec3::Zero();  // per unit gamma, and with the pairs' gammas
    for_each_liquid_pair(i, [&](Index j, const Vec3& r, Real d) {
      const Vec3 cohesion = -cohesion_scale * spline(d) / d * r;
      const Vec3 curvature = -curvature_scale * (normal[i] - normal[j]);
      if (fluid.phase[j] == own) {
        same += 2 * rho0 / (fluid.density[i] + fluid.density[j]) * (cohesion + curvature);
        return;
      }
      const FluidPhase& other = fm.phases[fluid.phase[j]];
      const Real pair_gamma = 0.5 * (gamma + other.surface_tension);
      if (pair_gamma == 0) return;
      const Real symmetry = 2 / (fluid.density[i] / rho0 + fluid.density[j] / other.rest_density);
      mixed += pair_gamma * symmetry * (cohesion + curvature);
    });
    v_new[i] += dt * fluid.inv_mass[i] * gamma * same + dt * fluid.inv_mass[i] * mixed;
  }
#pragma omp for schedule(static)
  for (Index i = 0; i < n; ++i) fluid.velocity[i] = v_new[i];
}

}  // namespace moreau
