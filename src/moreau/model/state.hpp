#pragma once
// The State: what a step changes — positions, velocities, multipliers, contacts and time.
// Buffers are sized when the state is created; contact buffers only grow.
#include <vector>

#include "moreau/collision/particle_contacts.hpp"
#include "moreau/continuum/continuum_state.hpp"
#include "moreau/fluids/fluid_state.hpp"
#include "moreau/model/particle_emitter.hpp"
#include "moreau/model/model.hpp"
#include "moreau/collision/particle_body_contacts.hpp"
#include "moreau/collision/rigid_contacts.hpp"
#include "moreau/sleeping/grain_sleep.hpp"
#include "moreau/solvers/nmd/nmd_row_memory.hpp"

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
  ParticleEmitterState emitters;                // what the particle emitters have released
  ContinuumState continuum;                     // the inelastic continua's deformation (per Model::continuum particle)
  NmdRowMemory nmd_rows;                        // nmd: last step's impulses of rows the families' multipliers do not hold

  /// Whether particle p takes part in the run: every particle but one its emitter has not
  /// released (model/particle_emitter.hpp).
  bool live(Index p) const { return emitters.unborn.empty() || !emitters.unborn[p]; }
  /// Whether particle p is held in its emitter's nozzle: it moves on at the emitter's velocity.
  bool held(Index p) const { return !emitters.held.empty() && emitters.held[p]; }
  /// The particles of the particle contacts that are live.
  const std::vector<Index>& live_contact_particles(const Model& model) const {
    return emitters.unborn.empty() ? model.contact_particle : emitters.live_contact_particle;
  }
};

/// Visits the live particles (State::live) of `object`, or of every object (-1), in the model's
/// particle arrays (fluid particles and bodies are elsewhere).
template <class F>
void for_each_live_particle(const Model& model, const State& state, Index object, F&& f) {
  const Index begin = object >= 0 ? model.objects[object].particle_begin : 0;
  const Index end = object >= 0 ? model.objects[object].particle_end : model.particle_count();
  for (Index p = begin; p < end; ++p)
    if (state.live(p)) f(p);
}

/// The inverse mass (1/kg) particle p has in a step's projections: the model's, or 0 while it is
/// held in its emitter's nozzle (model/particle_emitter.hpp).
inline Real moving_inverse_mass(const Model& model, const State& state, Index p) {
  return state.held(p) ? 0 : model.particle_inv_mass[p];
}

/// A state at rest in the model's rest configuration, with all buffers sized.
State make_rest_state(const Model& model);

}  // namespace moreau
