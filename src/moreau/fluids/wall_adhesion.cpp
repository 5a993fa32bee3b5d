#include "moreau/fluids/wall_adhesion.hpp"

#include "moreau/model/model.hpp"

namespace moreau {

namespace {

// z_a / r, c and k (see the header).
constexpr Real kReachInRadii = 5;
constexpr Real kLayerSum = 1.25;
constexpr Real kCalibration = 1.7;

}  // namespace

void apply_fluid_wall_adhesion(const Model& model, FluidState& fluid, Real dt, Real time) {
  const FluidModel& fm = model.fluid;
  bool any = false;
  for (const FluidPhase& p : fm.phases) any |= p.wall_adhesion > 0;
  if (!any || model.colliders.empty()) return;
  const Real r = fm.particle_radius, reach = kReachInRadii * r, area = kCalibration * 4 * r * r;
#pragma omp for schedule(static)
  for (Index i = 0; i < fluid.count; ++i) {
    const FluidPhase& phase = fm.phases[fluid.phase[i]];
    if (phase.wall_adhesion == 0 || phase.gas || fluid.inv_mass[i] == 0) continue;
    Vec3 force = Vec3::Zero();
    for (const Collider& c : model.colliders) {
      const ColliderDistance wall = collider_distance(c, c.position_at(time), fluid.position[i]);
      if (wall.distance >= reach) continue;
      const Real z = std::max<Real>(wall.distance, 0);
      force -= (phase.wall_adhesion * area * 2 * kLayerSum * (1 - z / reach) / reach) * wall.normal;
    }
    fluid.velocity[i] += dt * fluid.inv_mass[i] * force;
  }
}

}  // namespace moreau
