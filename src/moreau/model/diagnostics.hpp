#pragma once
// Whole-body quantities of a state: energies, momenta, centre of mass, constraint errors.
// `object` selects one object's particles and constraints; -1 means every object.
#include "moreau/model/state.hpp"

namespace moreau {

/// Calls f(i) for the live fluid particles of `object` (a fluid), of every fluid (-1), or of none
/// (an object that is not a fluid).
template <class F>
void for_each_fluid_particle(const Model& model, const State& state, Index object, F&& f) {
  const Index phase = object >= 0 ? model.objects[object].fluid_phase : -1;
  if (object >= 0 && phase < 0) return;
  for (Index i = 0; i < state.fluid.count; ++i)
    if (phase < 0 || state.fluid.phase[i] == phase) f(i);
}

/// Calls f(b) for the dynamic rigid bodies of `object` (or of every object, -1).
template <class F>
void for_each_dynamic_body(const Model& model, Index object, F&& f) {
  for (Index b = 0; b < model.rigid.count(); ++b)
    if (model.rigid.is_dynamic(b) && (object < 0 || model.rigid.body_object[b] == object)) f(b);
}

/// Translational plus rotational kinetic energy, J.
Real kinetic_energy(const Model& model, const State& state, Index object);
/// Gravitational potential energy -sum m g.x (zero at the origin), J.
Real potential_energy(const Model& model, const State& state, Index object);
/// Stored elastic energy of every compliant constraint, J.
Real elastic_energy(const Model& model, const State& state, Index object);
Vec3 linear_momentum(const Model& model, const State& state, Index object);
/// Angular momentum about `about`, kg m^2/s.
Vec3 angular_momentum(const Model& model, const State& state, Index object, const Vec3& about);
Vec3 center_of_mass(const Model& model, const State& state, Index object);

/// The largest violation of the object's constraints whose family reports under `error_name` (a
/// family's kErrorName, or "all"), each in its family's measure (max_error).
Real max_constraint_error(const Model& model, const State& state, Index object, std::string_view error_name);

}  // namespace moreau
