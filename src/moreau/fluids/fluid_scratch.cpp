#include "moreau/fluids/fluid_scratch.hpp"

#include "moreau/fluids/fluid_model.hpp"

namespace moreau {

void FluidScratch::fit(const FluidModel& fm) {
  const std::size_t capacity = fm.capacity, samples = fm.solid.size();
  const std::size_t coupled = fm.solid.coupled_particle.empty() ? 0 : fm.solid.coupled_particle.back() + 1;
  if (lambda.size() == capacity && solid_reaction.size() == samples && solid_share.size() == coupled) return;
  substep_start.assign(capacity, Vec3::Zero());
  lambda.assign(capacity, 0);
  correction.assign(capacity, Vec3::Zero());
  wall_gradient.assign(capacity, Vec3::Zero());
  reorder_vec.assign(capacity, Vec3::Zero());
  reorder_index.assign(capacity, 0);
  reorder_real.assign(capacity, 0);
  solid_reaction.assign(samples, Vec3::Zero());
  solid_inv_mass.assign(samples, 0);
  solid_share.assign(coupled, 1.0);
  solid_contacts.assign(capacity, 0);
}

}  // namespace moreau
