#include "moreau/fluids/fluid_state.hpp"

#include "moreau/fluids/fluid_heat.hpp"

namespace moreau {

FluidState make_fluid_state(const FluidModel& fm) {
  FluidState s;
  const std::size_t capacity = fm.capacity;
  s.count = fm.initial_count();
  s.position.assign(capacity, Vec3::Zero());
  s.velocity.assign(capacity, Vec3::Zero());
  s.phase.assign(capacity, 0);
  s.id.assign(capacity, 0);
  s.inv_mass.assign(capacity, 0);
  s.mass.assign(capacity, 0);
  s.enthalpy.assign(capacity, 0);
  s.smoke.assign(capacity, 0);
  s.release_time.assign(capacity, 0);
  s.viscosity.assign(capacity, 0);
  for (Index i = 0; i < s.count; ++i) {
    s.position[i] = fm.initial_position[i];
    s.velocity[i] = fm.initial_velocity[i];
    s.phase[i] = fm.initial_phase[i];
    s.id[i] = i;
    s.mass[i] = fm.phases[s.phase[i]].particle_mass;
    const FluidPhase& phase = fm.phases[s.phase[i]];
    s.enthalpy[i] = fluid_enthalpy(phase, phase.temperature);
    s.smoke[i] = phase.gas ? 1 : 0;
    set_fluid_particle_state(phase, s, i);
  }
  s.next_id = s.count;
  s.emitted_layers.assign(fm.emitters.size(), 0);
  s.listed_position = s.position;
  s.pressure.assign(capacity, 0);
  s.density.assign(capacity, 0);
  s.boundary_position.assign(fm.boundary.size(), Vec3::Zero());
  // Rows sized for a compressed neighbourhood; they grow (once) if a row ever overflows.
  s.fluid_neighbors.stride = 64;
  s.fluid_neighbors.count.assign(capacity, 0);
  s.fluid_neighbors.entries.assign(capacity * s.fluid_neighbors.stride, 0);
  s.boundary_neighbors.stride = 48;
  s.boundary_neighbors.count.assign(capacity, 0);
  s.boundary_neighbors.entries.assign(capacity * s.boundary_neighbors.stride, 0);
  s.solid_position.assign(fm.solid.size(), Vec3::Zero());
  s.solid_neighbors.stride = fm.solid.size() > 0 ? 48 : 1;
  s.solid_neighbors.count.assign(capacity, 0);
  s.solid_neighbors.entries.assign(capacity * s.solid_neighbors.stride, 0);
  s.solid_fluids.stride = 64;
  s.solid_fluids.count.assign(fm.solid.size(), 0);
  s.solid_fluids.entries.assign(fm.solid.size() * s.solid_fluids.stride, 0);
  s.frame = GridFrame{Vec3::Zero(), fm.support() + fm.neighbor_skin};
  return s;
}

}  // namespace moreau
