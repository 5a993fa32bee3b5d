#include "moreau/fluids/fluid_emitter.hpp"

#include "moreau/fluids/fluid_heat.hpp"
#include "moreau/fluids/fluid_state.hpp"
#include "moreau/model/model.hpp"

namespace moreau {

Index emit_fluid(const Model& model, FluidState& fluid, Real time) {
  const FluidModel& fm = model.fluid;
  const Real d = 2 * fm.particle_radius;
  // Free the particles whose layer has left its nozzle by now.
  for (Index i = 0; i < fluid.count; ++i) {
    Real& release = fluid.release_time[i];
    if (release > 0 && release <= time) {
      release = 0;
      set_fluid_particle_state(fm.phases[fluid.phase[i]], fluid, i);
    }
  }
  Index added = 0;
  for (std::size_t e = 0; e < fm.emitters.size(); ++e) {
    const FluidEmitter& emitter = fm.emitters[e];
    const FluidPhase& phase = fm.phases[emitter.phase];
    Index& released = fluid.emitted_layers[e];
    while (released < emitter.layers && emitter.birth(released, d) <= time) {
      const Real age = time - emitter.birth(released, d);
      const Real release = emitter.birth(released, d) + emitter.nozzle_length / emitter.speed;
      const Vec3 layer_center = emitter.center + emitter.speed * age * emitter.normal;
      for (const Vec3& offset : emitter.opening) {
        const Index i = fluid.count++;
        fluid.position[i] = fluid.listed_position[i] = layer_center + offset;
        fluid.velocity[i] = emitter.speed * emitter.normal;
        fluid.phase[i] = emitter.phase;
        fluid.id[i] = fluid.next_id++;
        fluid.mass[i] = phase.particle_mass;
        fluid.pressure[i] = 0;
        fluid.density[i] = phase.rest_density;
        fluid.enthalpy[i] = fluid_enthalpy(phase, phase.temperature);
        fluid.smoke[i] = phase.gas ? 1 : 0;
        fluid.release_time[i] = release > time ? release : 0;
        set_fluid_particle_state(phase, fluid, i);
        ++added;
      }
      ++released;
    }
  }
  if (added > 0) fluid.lists_stale = true;
  return added;
}

}  // namespace moreau
