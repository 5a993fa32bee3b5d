#pragma once
// The State: what a step changes — positions, velocities, multipliers, contacts and time.
// Buffers are sized when the state is created; contact buffers only grow.
#include <vector>

#include "moreau/collision/particle_contacts.hpp"
#include "moreau/fluids/fluid_state.hpp"
#include "moreau/model/model.hpp"
#include "moreau/collision/particle_body_contacts.hpp"
#include "moreau/collision/rigid_contacts.hpp"
#include "moreau/sleeping/grain_sleep.hpp"

namespace moreau {

struct State {
  Real time = 0;                        // s
  long step = 0;                        // completed steps

  std::vector<Vec3> position;           // m
  std::vector<Vec3> velocity;           // m/s
  std::vector<Vec3> angular_velocity;   // rad/s: grains turn (Model::particle_inv_inertia > 0); others keep 0

  // Multipliers of the particle constraint families (one vector per family, in list order), reset
  // at every substep and accumulated over its iterations. lambda / h^2 is the constraint force.
  ParticleFamilyMultipliers constraint_lambda;

  ColliderContacts collider_contacts;
  ParticleContacts particle_contacts;

  FluidState fluid;

  RigidBodyState rigid;
  RigidContacts rigid_contacts;
  ParticleBodyContacts particle_body_contacts;
  std::vector<JointMultipliers> joint_lambda;  // per joint, this substep (JointSlot)
  std::vector<SuctionCupState> suction;         // per Model::suction_cups
  GrainSleepState sleep;                        // sleeping grains (settings.sleep)
};

/// A state at rest in the model's rest configuration, with all buffers sized.
State make_rest_state(const Model& model);

}  // namespace moreau
