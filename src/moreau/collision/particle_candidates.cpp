#include "moreau/collision/particle_candidates.hpp"

#include "moreau/collision/particle_body_contacts.hpp"
#include "moreau/sleeping/grain_sleep.hpp"
#include "moreau/model/state.hpp"

namespace moreau {

void detect_particle_candidates(const Model& model, State& state, ContactScratch& scratch, int threads, bool bodies) {
  auto detect = [&] {
    detect_collider_contacts(model, state);
    detect_particle_contacts(model, state, scratch, threads);
    if (bodies) detect_particle_body_contacts(model, state);
  };
  // A woken island's grains may reach another sleeping island: wake until none is reached (at
  // most once per island), so no candidate pairs an awake particle with a sleeping grain.
  wake_moved_grains(model, state);  // a World state array written between steps
  detect();
  while (wake_reached_islands(state)) detect();
}

}  // namespace moreau
