#include "moreau/constraints/contact_rows.hpp"

#include "moreau/rigid/rigid_bodies.hpp"
#include "moreau/collision/rigid_contacts.hpp"

namespace moreau {

ContactPointAtPoses contact_point_at_poses(NormalFrame frame, const ContactGeometry& c, const Pose& pa, const Pose& pb) {
  const CorePoints cores = contact_cores(frame, c, pa, pb);
  const Vec3 n = contact_normal(frame, c, pa, pb, cores);
  const Vec3 p_a = cores.a - c.radius_a * n;
  const Vec3 p_b = cores.b + c.radius_b * n;
  return {n, p_a, p_b, (p_a - p_b).dot(n)};
}

ContactRows manifold_rows(const RigidManifold& mf, RigidContactPoint* points, const RigidBodyState& s,
                          const SubstepStart& start, ContactPoints which) {
  const Index a = mf.body_a, b = mf.body_b;
  const Pose pa{s.position[a], s.orientation[a]}, pb{s.position[b], s.orientation[b]};
  const Pose sa = start.body_pose(a), sb = start.body_pose(b);
  ContactRows rows;
  rows.end = {BodyEnd{BodyEndKind::body, a}, BodyEnd{BodyEndKind::body, b}};
  rows.static_friction = mf.static_friction;
  for (int i = 0; i < mf.count; ++i) {
    RigidContactPoint& c = points[i];
    const ContactPointAtPoses now = contact_point_at_poses(mf.frame, c.geometry, pa, pb);
    const Vec3& n = now.normal;
    const Vec3 &p_a = now.point_a, &p_b = now.point_b;
    c.normal = n;
    c.offset_a = p_a - pa.position;
    c.offset_b = p_b - pb.position;
    const Real depth = now.separation;
    if (depth >= 0 && which == ContactPoints::penetrating) continue;
    c.material_a = pa.orientation.conjugate() * c.offset_a;
    c.material_b = pb.orientation.conjugate() * c.offset_b;
    const Vec3 slip = (p_a - sa.to_world(c.material_a)) - (p_b - sb.to_world(c.material_b)) + c.stuck_slip;
    const Vec3 t1 = contact_tangent(n);
    const Vec3 t2 = n.cross(t1);
    const int r0 = 3 * rows.points;
    rows.direction[r0] = n;
    rows.direction[r0 + 1] = t1;
    rows.direction[r0 + 2] = t2;
    rows.C[r0] = depth;
    rows.C[r0 + 1] = slip.dot(t1);
    rows.C[r0 + 2] = slip.dot(t2);
    for (int r = r0; r < r0 + 3; ++r) {
      rows.offset_a[r] = c.offset_a;
      rows.offset_b[r] = c.offset_b;
    }
    rows.point[rows.points++] = i;
  }
  return rows;
}

}  // namespace moreau
