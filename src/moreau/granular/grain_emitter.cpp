#include "moreau/granular/grain_emitter.hpp"

#include <cmath>

#include "moreau/model/state.hpp"

namespace moreau {

namespace {

// Whether a live contact particle lies where the next layer would appear: within r + r_max of
// the plane at `offset` along the normal, and within r + reach of the axis.
bool layer_place_taken(const Model& model, const State& state, const GrainEmitter& emitter, Real offset) {
  for (Index p : state.emitters.live_contact_particle) {
    const Vec3 d = state.position[p] - emitter.center;
    const Real along = d.dot(emitter.normal);
    const Real r = model.particle_radius[p];
    if (std::abs(along - offset) >= r + emitter.max_radius) continue;
    if ((d - along * emitter.normal).squaredNorm() < (r + emitter.reach) * (r + emitter.reach)) return true;
  }
  return false;
}

}  // namespace

void prepare_grain_emitters(const Model& model, State& state) {
  GrainEmitterState& s = state.emitters;
  if (model.grain_emitters.empty()) return;
  s.released.assign(model.grain_emitters.size(), 0);
  s.wait.assign(model.grain_emitters.size(), 0);
  s.unborn.assign(model.particle_count(), 0);
  for (const GrainEmitter& e : model.grain_emitters)
    for (Index p = e.first; p < e.first + e.layers * e.per_layer; ++p) s.unborn[p] = 1;
  s.live_contact_particle.clear();
  for (Index p : model.contact_particle)
    if (!s.unborn[p]) s.live_contact_particle.push_back(p);
}

Index emit_grains(const Model& model, State& state) {
  GrainEmitterState& s = state.emitters;
  const Real time = state.time;
  Index added = 0;
  for (std::size_t k = 0; k < model.grain_emitters.size(); ++k) {
    const GrainEmitter& emitter = model.grain_emitters[k];
    Index& released = s.released[k];
    while (released < emitter.layers && emitter.due(released) + s.wait[k] <= time) {
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
        s.live_contact_particle.push_back(p);
      }
      added += emitter.per_layer;
      ++released;
    }
  }
  return added;
}

}  // namespace moreau
