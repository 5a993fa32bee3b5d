// Spherical (ball) joint: the anchors coincide, C = p_a - p_b = 0 (3 equality rows), with optional
// limits on the swing of b's x axis away from a's and on the twist about them.
//   swing  angle(x_a, x_b) <= swing, a rotation row about k = x_a x x_b / |x_a x x_b|
//   twist  the angle between the y axes about n = (x_a + x_b)/|x_a + x_b|, both projected on the
//          plane normal to n, in [twist_lower, twist_upper]; undefined (and left free) where the x
//          axes are opposite or a y axis lies along n
// Limit rows are present only while violated and may only push back (unilateral).
#include "moreau/constraints/joints/joint_row_blocks.hpp"
#include "moreau/constraints/joints/joint_type_rules.hpp"

namespace moreau {

namespace {

struct Twist {
  Vec3 axis;
  Real angle = 0;
};

bool spherical_twist(const JointEndPose& a, const JointEndPose& b, Twist& out) {
  const Vec3 mean = a.axis(0) + b.axis(0);
  if (mean.norm() <= 1e-9) return false;
  const Vec3 n = mean.normalized();
  const Vec3 ya = a.axis(1), yb = b.axis(1);
  const Vec3 pa = ya - n.dot(ya) * n, pb = yb - n.dot(yb) * n;
  if (pa.norm() <= 1e-9 || pb.norm() <= 1e-9) return false;
  out = {n, signed_angle(pa.normalized(), pb.normalized(), n)};
  return true;
}

Real swing_angle(const Vec3& xa, const Vec3& xb) { return std::atan2(xa.cross(xb).norm(), xa.dot(xb)); }

void spherical_rows(const JointRowContext& c, BodyRowSink& sink) {
  const Joint& j = c.joint;
  if (c.wants_others() && j.swing_limited) {
    const JointEndPose a = end_pose_a(c), b = end_pose_b(c);
    const Vec3 k = a.axis(0).cross(b.axis(0));
    const Real swing = swing_angle(a.axis(0), b.axis(0));
    if (swing > j.swing && k.norm() > 1e-12)
      sink.take(limit_row(j, a, b, swing, j.swing, -k.normalized(), true, JointSlot::swing, 0));
  }
  if (c.wants_others() && j.twist_limited) {
    const JointEndPose a = end_pose_a(c), b = end_pose_b(c);
    Twist t;
    if (spherical_twist(a, b, t) && (t.angle < j.twist_lower || t.angle > j.twist_upper))
      sink.take(limit_row(j, a, b, t.angle, std::clamp(t.angle, j.twist_lower, j.twist_upper), -t.axis, true,
                          JointSlot::twist, 0));
  }
  if (c.wants_equality()) sink.take(attachment_rows(j, end_pose_a(c), end_pose_b(c)));
}

JointError spherical_error(const Joint& j, const JointEndPose& a, const JointEndPose& b) {
  JointError e{(a.anchor() - b.anchor()).norm(), 0};
  if (j.swing_limited) e.angle = std::max(Real(0), swing_angle(a.axis(0), b.axis(0)) - j.swing);
  Twist t;
  if (j.twist_limited && spherical_twist(a, b, t)) e.angle = std::max(e.angle, excess(t.angle, j.twist_lower, j.twist_upper));
  return e;
}

}  // namespace

const JointTypeRules kSphericalJoint{
    spherical_rows, [](const Joint&) { return 3; }, [](const Joint& j) { return j.swing_limited || j.twist_limited; },
    spherical_error, no_coordinate};

}  // namespace moreau
