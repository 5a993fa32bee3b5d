#include "moreau/fluids/fluid_motion.hpp"

#include <algorithm>

#include "moreau/fluids/fluid_heat.hpp"
#include "moreau/model/model.hpp"

namespace moreau {

void predict_fluid(const Model& model, FluidState& fluid, FluidScratch& scratch, Real h) {
  const Vec3 dv = h * model.settings.gravity;
  const bool buoyant = model.fluid.buoyant;
  const Index n = fluid.count;
#pragma omp for schedule(static)
  for (Index i = 0; i < n; ++i) {
    scratch.substep_start[i] = fluid.position[i];
    fluid.pressure[i] = 0;
    if (fluid.inv_mass[i] == 0) {  // kinematic: a solid particle (v = 0) stays, a held one moves on
      fluid.position[i] += h * fluid.velocity[i];
      continue;
    }
    if (buoyant)
      fluid.velocity[i] += fluid_weight_factor(model.fluid.phases[fluid.phase[i]], fluid.enthalpy[i]) * dv;
    else
      fluid.velocity[i] += dv;
    fluid.position[i] += h * fluid.velocity[i];
  }
}

void apply_fluid_corrections(const Model& model, FluidState& fluid, const FluidScratch& scratch, Real h, Real time) {
  const FluidModel& fm = model.fluid;
  const Real r = fm.particle_radius;
  const Real pressure_scale = -1 / (fm.particle_volume * h * h);
  const Index n = fluid.count;
#pragma omp for schedule(static)
  for (Index i = 0; i < n; ++i) {
    Vec3 x = fluid.position[i] + scratch.correction[i];
    fluid.pressure[i] += pressure_scale * scratch.lambda[i];
    if (fluid.inv_mass[i] == 0) continue;  // kinematic: stays on its course
    for (const Collider& c : model.colliders) x = keep_clear_of_collider(c, c.position_at(time), x, r);
    fluid.position[i] = x;
  }
}

void update_fluid_velocity(FluidState& fluid, const FluidScratch& scratch, Real h) {
  const Real inv_h = 1 / h;
  const Index n = fluid.count;
#pragma omp for schedule(static)
  for (Index i = 0; i < n; ++i)
    if (fluid.inv_mass[i] != 0)  // a kinematic particle keeps its velocity
      fluid.velocity[i] = (fluid.position[i] - scratch.substep_start[i]) * inv_h;
}

Real fluid_cfl_number(const Model& model, FluidState& fluid, Real h) {
  Real v2 = 0;
  for (Index i = 0; i < fluid.count; ++i) v2 = std::max(v2, fluid.velocity[i].squaredNorm());
  const Real cfl = std::sqrt(v2) * h / (2 * model.fluid.particle_radius);
  fluid.max_cfl = std::max(fluid.max_cfl, cfl);
  if (cfl > model.fluid.cfl_limit) ++fluid.cfl_violations;
  return cfl;
}

}  // namespace moreau
