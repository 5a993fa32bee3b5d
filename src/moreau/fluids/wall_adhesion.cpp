#include "moreau/fluids/wall_adhesion.hpp"

#include <algorithm>

#include "moreau/model/model.hpp"

namespace moreau {

namespace {

// z_a / r and k (see the header).
constexpr Real kReachInRadii = 5;
constexpr Real kCalibration = 1.7;

// c = 1 / sum_k (1 - z_k / z_a)^2 over the lattice layers z_k = r, 3r, ... closer than z_a: a column
// of layers over the wall then has psi summing to 1 (1.25 for z_a = 5r).
Real layer_normalisation() {
  Real sum = 0;
  for (Real z = 1; z < kReachInRadii; z += 2) sum += (1 - z / kReachInRadii) * (1 - z / kReachInRadii);
  return 1 / sum;
}

}  // namespace

void apply_fluid_wall_adhesion(const Model& model, FluidState& fluid, Real dt, Real time) {
  const FluidModel& fm = model.fluid;
  bool any = false;
  for (const FluidPhase& p : fm.phases) any |= p.wall_adhesion > 0;
  if (!any || model.colliders.empty()) return;
  const Real r = fm.particle_radius, reach = kReachInRadii * r;
  // |F| / (W_a (1 - z / z_a)) = k (2r)^2 2c / z_a.
  const Real pull_per_adhesion = kCalibration * 4 * r * r * 2 * layer_normalisation() / reach;
#pragma omp for schedule(static)
  for (Index i = 0; i < fluid.count; ++i) {
    const FluidPhase& phase = fm.phases[fluid.phase[i]];
    if (phase.wall_adhesion == 0 || fluid.inv_mass[i] == 0) continue;  // none, or a held or solid particle
    Vec3 force = Vec3::Zero();
    for (const Collider& c : model.colliders) {
      if (!c.fluid_walls) continue;
      // Each wall in reach: a tank's two or three near an edge or corner, the nearest otherwise.
      ColliderDistance walls[3];
      const int count = collider_surfaces_within(c, c.position_at(time), fluid.position[i], reach, walls);
      for (int k = 0; k < count; ++k) {
        const Real z = std::max<Real>(walls[k].distance, 0);
        force -= (phase.wall_adhesion * pull_per_adhesion * (1 - z / reach)) * walls[k].normal;
      }
    }
    fluid.velocity[i] += dt * fluid.inv_mass[i] * force;
  }
}

}  // namespace moreau
