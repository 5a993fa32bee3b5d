#include "moreau/model/diagnostics.hpp"

#include <algorithm>

namespace moreau {

namespace {
// Visits the particles of `object` (or all) that move; pinned particles carry no momentum.
template <class F>
void for_each_particle(const Model& model, Index object, bool moving_only, F&& f) {
  const Index begin = object >= 0 ? model.objects[object].particle_begin : 0;
  const Index end = object >= 0 ? model.objects[object].particle_end : model.particle_count();
  for (Index p = begin; p < end; ++p)
    if (!moving_only || model.particle_inv_mass[p] > 0) f(p);
}
}  // namespace

Real kinetic_energy(const Model& model, const State& state, Index object) {
  Real e = 0;
  for_each_particle(model, object, true, [&](Index p) { e += 0.5 * model.particle_mass[p] * state.velocity[p].squaredNorm(); });
  return e;
}

Real potential_energy(const Model& model, const State& state, Index object) {
  Real e = 0;
  for_each_particle(model, object, true,
                    [&](Index p) { e -= model.particle_mass[p] * model.settings.gravity.dot(state.position[p]); });
  return e;
}

Real elastic_energy(const Model& model, const State& state, Index object) {
  const Vec3* x = state.position.data();
  return distance_energy(model.distance, x, object) + dihedral_bending_energy(model.bending, x, object) +
         isometric_bending_energy(model.isometric_bending, x, object) +
         triangle_strain_energy(model.triangle_strain, x, object) + neo_hookean_energy(model.neo_hookean, x, object) +
         tet_volume_energy(model.tet_volume, x, object) + attachment_energy(model.attachment, x, object);
}

Vec3 linear_momentum(const Model& model, const State& state, Index object) {
  Vec3 p = Vec3::Zero();
  for_each_particle(model, object, true, [&](Index i) { p += model.particle_mass[i] * state.velocity[i]; });
  return p;
}

Vec3 angular_momentum(const Model& model, const State& state, Index object, const Vec3& about) {
  Vec3 L = Vec3::Zero();
  for_each_particle(model, object, true,
                    [&](Index i) { L += model.particle_mass[i] * (state.position[i] - about).cross(state.velocity[i]); });
  return L;
}

Vec3 center_of_mass(const Model& model, const State& state, Index object) {
  Vec3 c = Vec3::Zero();
  Real m = 0;
  for_each_particle(model, object, false, [&](Index i) {
    c += model.particle_mass[i] * state.position[i];
    m += model.particle_mass[i];
  });
  return m > 0 ? Vec3(c / m) : c;
}

Real max_constraint_error(const Model& model, const State& state, Index object, ConstraintFamily family) {
  const Vec3* x = state.position.data();
  const bool all = family == ConstraintFamily::all;
  Real e = 0;
  if (all || family == ConstraintFamily::distance) e = std::max(e, distance_max_error(model.distance, x, object));
  if (all || family == ConstraintFamily::bending) {
    e = std::max(e, dihedral_bending_max_error(model.bending, x, object));
    e = std::max(e, isometric_bending_max_error(model.isometric_bending, x, object));
  }
  if (all || family == ConstraintFamily::triangle_strain)
    e = std::max(e, triangle_strain_max_error(model.triangle_strain, x, object));
  if (all || family == ConstraintFamily::neo_hookean_volume)
    e = std::max(e, neo_hookean_max_volume_error(model.neo_hookean, x, object));
  if (all || family == ConstraintFamily::tet_volume) e = std::max(e, tet_volume_max_error(model.tet_volume, x, object));
  if (all || family == ConstraintFamily::attachment) e = std::max(e, attachment_max_error(model.attachment, x, object));
  return e;
}

}  // namespace moreau
