#include "moreau/model/particle_emitter.hpp"

#include <cmath>

#include "moreau/model/state.hpp"

namespace moreau {

namespace {

// Whether a live contact particle lies where the next layer would appear: within r + r_max of
// the plane at `offset` along the normal, and within r + reach of the axis.
bool layer_place_taken(const Model& model, const State& state, const ParticleEmitter& emitter, Real offset) {
  for (Index p : state.emitters.live_contact_particle) {
    const Vec3 d = state.position[p] - emitter.center;
    const Real along = d.dot(emitter.normal);
    const Real r = model.particle_radius[p];
    if (std::abs(along - offset) >= r + emitter.max_radius) continue;
    if ((d - along * emitter.normal).squaredNorm() < (r + emitter.reach) * (r + emitter.reach)) return true;
  }
  return false;
}

// Frees the layers that have travelled the nozzle's length past the opening by `time`.
void free_nozzle_layers(const ParticleEmitter& emitter, ParticleEmitterState& s, std::size_t k, Real time) {
  Index& freed = s.freed[k];
  const std::vector<Real>& left = s.left_opening[k];
  while (freed < s.released[k] && left[freed] + emitter.nozzle_length / emitter.speed <= time) {
    const Index begin = emitter.first + freed * emitter.per_layer;
    for (Index p = begin; p < begin + emitter.per_layer; ++p) s.held[p] = 0;
    ++freed;
  }
}

}  // namespace

void prepare_particle_emitters(const Model& model, State& state) {
  ParticleEmitterState& s = state.emitters;
  if (model.particle_emitters.empty()) return;
  const std::size_t count = model.particle_emitters.size();
  s.released.assign(count, 0);
  s.freed.assign(count, 0);
  s.left_opening.assign(count, {});
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
    while (released < emitter.layers && emitter.due(released) + s.wait[k] <= time) {
      const Real left_opening = emitter.due(released) + s.wait[k];
      const Real offset = emitter.speed * (time - left_opening);
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
      s.left_opening[k].push_back(left_opening);
      added += emitter.per_layer;
      ++released;
    }
    if (emitter.nozzle_length > 0) free_nozzle_layers(emitter, s, k, time);
  }
  return added;
}

}  // namespace moreau
