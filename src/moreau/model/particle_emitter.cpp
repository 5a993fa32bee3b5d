#include "moreau/model/particle_emitter.hpp"

#include <cmath>

#include "moreau/model/state.hpp"

namespace moreau {

namespace {

// Whether a live contact particle (not held in a nozzle, with `skip_held`) lies within r + reach
// of the opening's axis, r its radius, at a distance `along` past the opening's plane that
// `in_range(along, r)` accepts.
template <class InRange>
bool occupied(const Model& model, const State& state, const ParticleEmitter& emitter, bool skip_held, InRange in_range) {
  for (Index p : state.emitters.live_contact_particle) {
    if (skip_held && state.held(p)) continue;
    const Vec3 d = state.position[p] - emitter.center;
    const Real along = d.dot(emitter.normal);
    const Real r = model.particle_radius[p];
    if (!in_range(along, r)) continue;
    if ((d - along * emitter.normal).squaredNorm() < (r + emitter.reach) * (r + emitter.reach)) return true;
  }
  return false;
}

// Whether a particle lies where the next layer would appear: within r + r_max of the plane at
// `offset` along the normal.
bool layer_place_taken(const Model& model, const State& state, const ParticleEmitter& emitter, Real offset) {
  return occupied(model, state, emitter, false,
                  [&](Real along, Real r) { return std::abs(along - offset) < r + emitter.max_radius; });
}

// Whether a particle that is not held lies in the nozzle: from r + r_max behind the opening's
// plane to half a spacing short of the nozzle's end. The layers it frees are at its end and move
// away; a particle further in is material the stream has piled up against the spout, or another
// object's.
bool nozzle_blocked(const Model& model, const State& state, const ParticleEmitter& emitter) {
  const Real end = emitter.nozzle_length - 0.5 * emitter.spacing;
  return occupied(model, state, emitter, true,
                  [&](Real along, Real r) { return along > -(r + emitter.max_radius) && along < end; });
}

// Frees the layers that have travelled the nozzle's length past the opening, and sets the held
// ones moving at v n, or standing while the nozzle is blocked.
void update_nozzle(const Model& model, State& state, const ParticleEmitter& emitter, std::size_t k, bool blocked) {
  ParticleEmitterState& s = state.emitters;
  Index& freed = s.freed[k];
  auto travelled = [&](Index layer) {
    const Index p = emitter.first + layer * emitter.per_layer;
    return (state.position[p] - model.particle_rest_position[p]).dot(emitter.normal);
  };
  while (freed < s.released[k] && travelled(freed) >= emitter.nozzle_length) {
    const Index begin = emitter.first + freed * emitter.per_layer;
    for (Index p = begin; p < begin + emitter.per_layer; ++p) s.held[p] = 0;
    ++freed;
  }
  const Vec3 velocity = blocked ? Vec3::Zero() : Vec3(emitter.speed * emitter.normal);
  for (Index p = emitter.first + freed * emitter.per_layer; p < emitter.first + s.released[k] * emitter.per_layer; ++p)
    state.velocity[p] = velocity;
}

}  // namespace

void prepare_particle_emitters(const Model& model, State& state) {
  ParticleEmitterState& s = state.emitters;
  if (model.particle_emitters.empty()) return;
  const std::size_t count = model.particle_emitters.size();
  s.released.assign(count, 0);
  s.freed.assign(count, 0);
  s.wait.assign(count, 0);
  s.unborn.assign(model.particle_count(), 0);
  s.held.clear();
  for (const ParticleEmitter& e : model.particle_emitters) {
    for (Index p = e.first; p < e.first + e.layers * e.per_layer; ++p) s.unborn[p] = 1;
    if (e.nozzle_length > 0) s.held.assign(model.particle_count(), 0);
  }
  s.live_contact_particle.clear();
  for (Index p : model.contact_particle)
    if (!s.unborn[p]) s.live_contact_particle.push_back(p);
}

Index emit_particles(const Model& model, State& state) {
  ParticleEmitterState& s = state.emitters;
  const Real time = state.time;
  Index added = 0;
  for (std::size_t k = 0; k < model.particle_emitters.size(); ++k) {
    const ParticleEmitter& emitter = model.particle_emitters[k];
    Index& released = s.released[k];
    // A blocked nozzle's held layers stand still for this step, so every later layer is due a step
    // later; with none held, a layer due waits as for a covered opening.
    const bool nozzle = emitter.nozzle_length > 0 && (released < emitter.layers || s.freed[k] < released);
    const bool blocked = nozzle && nozzle_blocked(model, state, emitter);
    if (blocked && s.freed[k] < released)
      s.wait[k] += model.settings.dt;
    else if (blocked && released < emitter.layers && emitter.due(released) + s.wait[k] <= time)
      s.wait[k] = time + 0.5 * model.settings.dt - emitter.due(released);  // try again at the next step
    while (!blocked && released < emitter.layers && emitter.due(released) + s.wait[k] <= time) {
      const Real age = time - (emitter.due(released) + s.wait[k]);
      const Real offset = emitter.speed * age;
      if (layer_place_taken(model, state, emitter, offset)) {
        s.wait[k] = time + 0.5 * model.settings.dt - emitter.due(released);  // try again at the next step
        break;
      }
      const Vec3 velocity = emitter.speed * emitter.normal;
      const Index begin = emitter.first + released * emitter.per_layer;
      for (Index p = begin; p < begin + emitter.per_layer; ++p) {
        state.position[p] = model.particle_rest_position[p] + offset * emitter.normal;
        state.velocity[p] = velocity;
        state.angular_velocity[p].setZero();
        state.sleep.still_from[p] = state.position[p];
        state.sleep.still_time[p] = 0;
        s.unborn[p] = 0;
        if (emitter.nozzle_length > 0) s.held[p] = 1;
        s.live_contact_particle.push_back(p);
      }
      added += emitter.per_layer;
      ++released;
    }
    if (nozzle) update_nozzle(model, state, emitter, k, blocked);
    if (emitter.nozzle_length <= 0) s.freed[k] = released;  // no nozzle: each layer goes at once
  }
  return added;
}

}  // namespace moreau
