#include "moreau/solvers/xpbd/particle_body_contact_projection.hpp"

#include <algorithm>

#include "moreau/constraints/particle_body_contact_rows.hpp"
#include "moreau/constraints/particle_contact_rows.hpp"
#include "moreau/model/state.hpp"
#include "moreau/rigid/body_handle.hpp"
#include "moreau/rigid/rigid_motion.hpp"
#include "moreau/solvers/xpbd/particle_contact_projection.hpp"

namespace moreau {

void reset_particle_body_contacts(State& state) {
  std::fill(state.particle_body_contacts.lambda_normal.begin(), state.particle_body_contacts.lambda_normal.end(), 0);
}

void project_particle_body_contacts(const Model& model, State& state, const SubstepStart& start, Real h) {
  ParticleBodyContacts& c = state.particle_body_contacts;
  RigidBodyState& s = state.rigid;
  for (size_t q = 0; q < c.size(); ++q) {
    const auto [b, p] = c.pair[q];
    const ParticleBodyNormal near = nearest_on_body(model, state, b, state.position[p]);
    const Real C = near.surface.distance - model.particle_collider_gap[p];  // the normal row
    const ContactSpring& spring = c.spring[q];
    // A hard contact acts while it overlaps; a spring also while its push lasts, to let go of it.
    if (C >= 0 && (!spring.soft() || c.lambda_normal[q] <= 0)) continue;
    const BodyHandle hp = particle_handle(state.position[p], moving_inverse_mass(model, state, p)), hb = rigid_body_handle(model.rigid, s, b);
    const Vec3& n = near.normal;
    c.normal[q] = n;
    c.offset[q] = near.offset;
    if (spring.soft()) {
      const Real w = hp.positional_weight(Vec3::Zero(), n) + hb.positional_weight(near.offset, n);
      const Real motion = n.dot(particle_body_slip(state, start, b, p, near.surface.point));
      const Real dl = compliant_normal_increment(spring, C, motion, c.lambda_normal[q], w, 0, h);
      c.lambda_normal[q] += dl;
      hp.apply_position_impulse(dl * n, Vec3::Zero());
      hb.apply_position_impulse(-dl * n, near.offset);
    } else {
      apply_positional_correction(hp, hb, n, C, Vec3::Zero(), near.offset, 0, c.lambda_normal[q]);
    }
    // Static friction: the slip of the particle against the body's material point over the substep.
    const Vec3 dp_t = tangential_part(particle_body_slip(state, start, b, p, near.surface.point), n);
    const Real slip = dp_t.norm();
    if (slip <= 0) continue;
    const Vec3 t = dp_t / slip;
    const Vec3 r = (s.position[b] + s.orientation[b] * near.surface.point) - s.position[b];  // as the slip's point
    const Real w = hp.positional_weight(Vec3::Zero(), t) + hb.positional_weight(r, t);
    if (w <= 0 || slip / w >= c.static_friction[q] * c.lambda_normal[q]) continue;
    Real lambda_t = 0;
    apply_positional_correction(hp, hb, t, slip, Vec3::Zero(), r, 0, lambda_t);
  }
}

void particle_body_contact_velocities(const Model& model, State& state, const Vec3* velocity_before,
                                      const RigidSubstepStart& bodies_before, Real h) {
  ParticleBodyContacts& c = state.particle_body_contacts;
  const RigidBodyModel& m = model.rigid;
  RigidBodyState& s = state.rigid;
  const Real g = model.settings.gravity.norm();
  for (size_t q = 0; q < c.size(); ++q) {
    if (c.lambda_normal[q] <= 0) continue;
    const auto [b, p] = c.pair[q];
    const Vec3& n = c.normal[q];
    const Vec3& r = c.offset[q];
    const BodyVelocityHandle vp = particle_velocity_handle(state.velocity[p], moving_inverse_mass(model, state, p));
    const BodyVelocityHandle vb = rigid_body_velocity_handle(m, s, b);
    const Vec3 v = vp.point_velocity(Vec3::Zero()) - vb.point_velocity(r);
    const Vec3 before = velocity_before[p] - (bodies_before.velocity[b] + bodies_before.angular_velocity[b].cross(r));
    const Real w = vp.weight(Vec3::Zero(), n) + vb.weight(r, n);
    // A spring's bounce is its own: a soft contact gets dynamic friction only.
    const Vec3 dv = c.spring[q].soft()
                        ? friction_velocity_change(v, n, c.lambda_normal[q], w, c.dynamic_friction[q], h)
                        : contact_velocity_change(v, before, n, c.lambda_normal[q], w, c.dynamic_friction[q],
                                                  c.restitution[q], h, g);
    apply_relative_velocity_change(vp, vb, dv, Vec3::Zero(), r);
  }
}

}  // namespace moreau
