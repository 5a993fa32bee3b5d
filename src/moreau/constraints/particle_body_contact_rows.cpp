#include "moreau/constraints/particle_body_contact_rows.hpp"

#include "moreau/constraints/contact_rows.hpp"
#include "moreau/model/state.hpp"
#include "moreau/collision/narrow_phase.hpp"

namespace moreau {

ParticleBodyNormal nearest_on_body(const Model& model, const State& state, Index b, const Vec3& x) {
  const Pose pose{state.rigid.position[b], state.rigid.orientation[b]};
  const SurfacePoint sp = nearest_surface_point(model.rigid.body_shape[b], pose.to_local(x));
  return {sp, pose.orientation * sp.normal, pose.orientation * sp.point};
}

Vec3 particle_body_slip(const State& state, const SubstepStart& start, Index b, Index p, const Vec3& local) {
  const RigidBodyState& s = state.rigid;
  const Vec3 body_point = s.position[b] + s.orientation[b] * local;
  const Vec3 body_start = start.body_position[b] + start.body_orientation[b] * local;
  return (state.position[p] - start.particle_position[p]) - (body_point - body_start);
}

ParticleBodyContactRows particle_body_rows(const Model& model, const State& state, const SubstepStart& start, Index b,
                                          Index p, Real static_friction, ContactPoints which) {
  const std::array<BodyEnd, 2> ends{BodyEnd{BodyEndKind::particle, p}, BodyEnd{BodyEndKind::body, b}};
  ParticleBodyContactRows result{BodyRows::zero(ends, 3, 0), static_friction};
  BodyRows& rows = result.rows;
  const ParticleBodyNormal near = nearest_on_body(model, state, b, state.position[p]);
  const Real C = near.surface.distance - model.particle_collider_gap[p];
  if (C >= 0 && which == ContactPoints::penetrating) return result;
  const Vec3& n = near.normal;
  const Vec3 slip = particle_body_slip(state, start, b, p, near.surface.point);
  const Vec3 t1 = contact_tangent(n), t2 = n.cross(t1);
  rows.C << C, slip.dot(t1), slip.dot(t2);
  rows.set_point_row(0, n, Vec3::Zero(), near.offset);
  rows.set_point_row(1, t1, Vec3::Zero(), near.offset);
  rows.set_point_row(2, t2, Vec3::Zero(), near.offset);
  rows.make_unilateral(0, true);
  return result;
}

}  // namespace moreau
