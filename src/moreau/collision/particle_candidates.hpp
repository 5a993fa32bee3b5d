#pragma once
// The step's contact candidates of particles: with colliders, with each other and, when the
// scene has them, with rigid bodies. Sleeping islands of grains (sleeping/grain_sleep.hpp) that
// were moved from outside or that a candidate reaches are woken first and the candidates sought
// again, so a woken island enters the step with all its contacts.
#include "moreau/collision/particle_contacts.hpp"

namespace moreau {

void detect_particle_candidates(const Model& model, State& state, ContactScratch& scratch, int threads, bool bodies);

}  // namespace moreau
