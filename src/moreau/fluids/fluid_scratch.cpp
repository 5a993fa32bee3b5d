#include "moreau/fluids/fluid_scratch.hpp"

#include <algorithm>

#include "moreau/fluids/fluid_model.hpp"

namespace moreau {

void FluidScratch::fit(const FluidModel& fm) {
  const std::size_t capacity = fm.capacity, samples = fm.solid.size();
  const std::size_t coupled = fm.solid.coupled_particle.empty() ? 0 : fm.solid.coupled_particle.back() + 1;
  const bool implicit_viscosity = fm.viscosity_solver == ViscositySolver::implicit_solve;
  const std::size_t solve_size = implicit_viscosity ? capacity : 0;
  const std::size_t heat_size = fm.thermal ? capacity : 0;
  const bool rough_solids = implicit_viscosity && fm.solid.any_friction;
  const std::size_t rough_samples = rough_solids ? samples : 0, rough_size = rough_solids ? capacity : 0;
  std::size_t rough_bodies = 0;
  if (rough_solids)
    for (Index b : fm.solid.sampled_body) rough_bodies = std::max(rough_bodies, static_cast<std::size_t>(b) + 1);
  if (lambda.size() == capacity && solid_reaction.size() == samples && solid_share.size() == coupled &&
      solve_residual.size() == solve_size && temperature.size() == heat_size && stress_slope.size() == rough_size &&
      solid_viscous_force.size() == rough_samples && solid_wall_velocity.size() == rough_samples &&
      rough_body.size() == rough_bodies)
    return;
  substep_start.assign(capacity, Vec3::Zero());
  lambda.assign(capacity, 0);
  correction.assign(capacity, Vec3::Zero());
  wall_gradient.assign(capacity, Vec3::Zero());
  reorder_vec.assign(capacity, Vec3::Zero());
  reorder_index.assign(capacity, 0);
  reorder_real.assign(capacity, 0);
  temperature.assign(heat_size, 0);
  heat_change.assign(heat_size, 0);
  solid_reaction.assign(samples, Vec3::Zero());
  solid_inv_mass.assign(samples, 0);
  solid_share.assign(coupled, 1.0);
  solid_contacts.assign(capacity, 0);
  viscous_change.assign(solve_size, Vec3::Zero());
  gradient_correction.assign(solve_size, Mat3::Identity());
  fluid_gradient_correction.assign(solve_size, Mat3::Identity());
  corrected_stress.assign(solve_size, Mat3::Zero());
  stress_viscosity.assign(solve_size, 0);
  wall_sum.assign(solve_size, Vec3::Zero());
  wall_velocity_sum.assign(solve_size, Mat3::Zero());
  velocity_gradient.assign(solve_size, Mat3::Zero());
  solid_viscous_force.assign(rough_samples, Vec3::Zero());
  solid_wall_velocity.assign(rough_samples, Vec3::Zero());
  rough_body.assign(rough_bodies, RigidSurfaceMotion{});
  stress_slope.assign(rough_size, {Mat3::Zero(), Mat3::Zero(), Mat3::Zero()});
  for (std::vector<Vec3>* v : {&solve_residual, &solve_shadow, &solve_direction, &solve_direction_image,
                                &solve_preconditioned, &solve_intermediate, &solve_intermediate_image})
    v->assign(solve_size, Vec3::Zero());
  inverse_diagonal.assign(solve_size, Mat3::Identity());
}

}  // namespace moreau
