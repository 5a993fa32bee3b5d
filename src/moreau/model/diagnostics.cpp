#include "moreau/model/diagnostics.hpp"

#include <algorithm>

#include "moreau/continuum/plastic_flow.hpp"
#include "moreau/rods/rod_geometry.hpp"

namespace moreau {

namespace {
// Visits (mass, position, velocity) of the particles of `object` (or of all objects, -1),
// including fluid particles. With moving_only, pinned particles (no momentum) are skipped.
template <class F>
void for_each_mass_point(const Model& model, const State& state, Index object, bool moving_only, F&& f) {
  for_each_live_particle(model, state, object, [&](Index p) {
    if (!moving_only || model.particle_inv_mass[p] > 0) f(model.particle_mass[p], state.position[p], state.velocity[p]);
  });
  const FluidState& fluid = state.fluid;
  for_each_fluid_particle(model, state, object, [&](Index i) { f(fluid.mass[i], fluid.position[i], fluid.velocity[i]); });
  for_each_dynamic_body(model, object, [&](Index b) {
    f(model.rigid.body_mass[b], state.rigid.position[b], state.rigid.velocity[b]);
  });
}

// Visits (inverse inertia, angular velocity) of the turning grains of `object` (or of all, -1).
template <class F>
void for_each_turning_grain(const Model& model, const State& state, Index object, F&& f) {
  for_each_live_particle(model, state, object, [&](Index p) {
    if (model.particle_inv_inertia[p] > 0) f(model.particle_inv_inertia[p], state.angular_velocity[p]);
  });
}

// Spin angular momentum I w of body b (world frame), kg m^2/s.
Vec3 body_spin(const Model& model, const State& state, Index b) {
  const Quat& q = state.rigid.orientation[b];
  return q * Vec3(model.rigid.body_inertia[b].cwiseProduct(q.conjugate() * state.rigid.angular_velocity[b]));
}
}  // namespace

Real kinetic_energy(const Model& model, const State& state, Index object) {
  Real e = 0;
  for_each_mass_point(model, state, object, true, [&](Real m, const Vec3&, const Vec3& v) { e += 0.5 * m * v.squaredNorm(); });
  for_each_dynamic_body(model, object,
                        [&](Index b) { e += 0.5 * state.rigid.angular_velocity[b].dot(body_spin(model, state, b)); });
  for_each_turning_grain(model, state, object, [&](Real inv_inertia, const Vec3& w) { e += 0.5 * w.squaredNorm() / inv_inertia; });
  return e;
}

Real potential_energy(const Model& model, const State& state, Index object) {
  Real e = 0;
  for_each_mass_point(model, state, object, true,
                      [&](Real m, const Vec3& x, const Vec3&) { e -= m * model.settings.gravity.dot(x); });
  return e;
}

Real elastic_energy(const Model& model, const State& state, Index object) {
  Real energy = 0;
  for_each_family(model.constraints, [&](const auto& family, int) { energy += family.energy(state.position.data(), object); });
  for (const RodModel& rod : model.rods)
    if (object < 0 || rod.object == object) energy += rod_elastic_energy(rod, model.joints, state);
  energy += shape_match_energy(model.shape_matching, state.position.data(), object);
  // The continua's stored energy sum V^0 Psi(F) of the elastic deformation gradients.
  const ContinuumModel& continuum = model.continuum;
  for (Index i = 0; i < state.continuum.size(); ++i) {
    if (object >= 0 && model.particle_object[continuum.particle[i]] != object) continue;
    const ContinuumMaterial& material = continuum.materials[continuum.material[i]];
    const Vec3 sigma = rotation_svd(state.continuum.deformation[i]).sigma.cwiseMax(kMinContinuumStretch);
    energy += continuum.rest_volume[i] *
              hencky_energy(continuum_lame(material, state.continuum.plastic_volume[i]), sigma);
  }
  return energy;
}

Vec3 linear_momentum(const Model& model, const State& state, Index object) {
  Vec3 p = Vec3::Zero();
  for_each_mass_point(model, state, object, true, [&](Real m, const Vec3&, const Vec3& v) { p += m * v; });
  return p;
}

Vec3 angular_momentum(const Model& model, const State& state, Index object, const Vec3& about) {
  Vec3 L = Vec3::Zero();
  for_each_mass_point(model, state, object, true,
                      [&](Real m, const Vec3& x, const Vec3& v) { L += m * (x - about).cross(v); });
  for_each_dynamic_body(model, object, [&](Index b) { L += body_spin(model, state, b); });
  for_each_turning_grain(model, state, object, [&](Real inv_inertia, const Vec3& w) { L += w / inv_inertia; });
  return L;
}

Vec3 center_of_mass(const Model& model, const State& state, Index object) {
  Vec3 c = Vec3::Zero();
  Real mass = 0;
  for_each_mass_point(model, state, object, false, [&](Real m, const Vec3& x, const Vec3&) {
    c += m * x;
    mass += m;
  });
  return mass > 0 ? Vec3(c / mass) : c;
}

Real max_constraint_error(const Model& model, const State& state, Index object, std::string_view error_name) {
  Real e = 0;
  for_each_family(model.constraints, [&](const auto& family, int) {
    if (error_name == "all" || error_name == family.kErrorName)
      e = std::max(e, family.max_error(state.position.data(), object));
  });
  return e;
}

}  // namespace moreau
