#include "moreau/rods/rod_geometry.hpp"

#include <cmath>

#include "moreau/constraints/joints/joint_frames.hpp"

namespace moreau {

namespace {

// The point at `offset` (segment frame) of segment s, and its velocity.
Vec3 segment_point(const RigidBodyState& bodies, Index s, const Vec3& offset) {
  return bodies.position[s] + bodies.orientation[s] * offset;
}
Vec3 segment_point_velocity(const RigidBodyState& bodies, Index s, const Vec3& offset) {
  return bodies.velocity[s] + bodies.angular_velocity[s].cross(bodies.orientation[s] * offset);
}

// The two segment ends at centreline point k (the same segment twice at the rod's ends).
struct PointEnds {
  Index before, after;
  Vec3 offset_before, offset_after;
};

PointEnds point_ends(const RodModel& rod, Index k) {
  const Index s = rod.segment_of_point(k);
  PointEnds e{rod.first_body + s, rod.first_body + s, rod.point_in_segment(k), rod.point_in_segment(k)};
  if (k > 0 && k < rod.segments) {
    e.before = rod.first_body + k - 1;
    e.offset_before = Vec3(0, rod.segment_length[k - 1] / 2, 0);
  }
  return e;
}

}  // namespace

Vec3 rod_point(const RodModel& rod, const RigidBodyState& bodies, Index k) {
  const PointEnds e = point_ends(rod, k);
  return 0.5 * (segment_point(bodies, e.before, e.offset_before) + segment_point(bodies, e.after, e.offset_after));
}

Vec3 rod_point_velocity(const RodModel& rod, const RigidBodyState& bodies, Index k) {
  const PointEnds e = point_ends(rod, k);
  return 0.5 * (segment_point_velocity(bodies, e.before, e.offset_before) +
                segment_point_velocity(bodies, e.after, e.offset_after));
}

Real junction_twist(const Joint& junction, const State& state) {
  // The relative rotation split into a swing of the tangent and a twist about it: the twist angle
  // is 2 atan2(q_x, q_w) with x the tangent.
  const Quat q = end_pose(state, junction.ends[0]).frame().conjugate() * end_pose(state, junction.ends[1]).frame();
  Real angle = 2 * std::atan2(q.x(), q.w());
  if (angle > kPi) angle -= 2 * kPi;
  if (angle <= -kPi) angle += 2 * kPi;
  return angle;
}

Real rod_twist(const RodModel& rod, const std::vector<Joint>& joints, const State& state) {
  Real twist = 0;
  for (Index k = 0; k + 1 < rod.segments; ++k) twist += junction_twist(joints[rod.first_joint + k], state);
  // A clamped start turns the first segment against the world: that is twist of the rod too.
  if (rod.start_joint >= 0 && !joints[rod.start_joint].rod_pinned) twist += junction_twist(joints[rod.start_joint], state);
  return twist;
}

namespace {

// Sums C^2 / (2 alpha) over the compliant rows it is handed.
class EnergySink final : public BodyRowSink {
 public:
  void take(const BodyRows& rows) override {
    for (int r = 0; r < rows.size(); ++r)
      if (rows.compliance[r] > 0) energy += rows.C[r] * rows.C[r] / (2 * rows.compliance[r]);
  }
  Real energy = 0;
};

}  // namespace

Real rod_elastic_energy(const RodModel& rod, const std::vector<Joint>& joints, const State& state) {
  EnergySink sink;
  for (Index k = 0; k < rod.joint_count; ++k)
    joint_rows({state, joints[rod.first_joint + k], 0, 0, JointRowSet::equality}, sink);
  return sink.energy;
}

}  // namespace moreau
