// Hinge (revolute) joint: b turns relative to a about a's x axis only.
//   alignment  C_k = y_k . (x_b x x_a) = 0 for y_k the two axes of a across the hinge, 2 rows,
//              angular compliance; de = x_b x (dtheta_a x x_a) + (dtheta_b x x_b) x x_a
//              = ((x_a.x_b) I - x_a x_b^T) dtheta_a - ((x_a.x_b) I - x_b x_a^T) dtheta_b, and y_k
//              turns with a, so d(y_k . e) gains (y_k x e) . dtheta_a
//   angle      phi = atan2((y_a x y_b) . x_a, y_a . y_b), b relative to a about x_a
//   limits     phi in [lower, upper]: a rotation row about -x_a while violated, unilateral
//   drive      C = phi - phi_target wrapped into (-pi, pi] (a target across the seam turns the
//              short way); phi_target = phi_start + h omega for a velocity drive; bounded torque
//   attachment C = p_a - p_b = 0, 3 rows
// Alignment and attachment are equality rows the direct tree solver may take (5 rows).
#include <cmath>

#include "moreau/constraints/joints/joint_row_blocks.hpp"
#include "moreau/constraints/joints/joint_type_rules.hpp"

namespace moreau {

namespace {

BodyRows alignment_rows(const Joint& j, const JointEndPose& a, const JointEndPose& b) {
  BodyRows rows = BodyRows::zero(j.bodies(), 2, JointSlot::orientation);
  rows.compliance.setConstant(j.angular_compliance);
  const Vec3 xa = a.axis(0), xb = b.axis(0), e = xb.cross(xa);
  const Real cosine = xa.dot(xb);
  const Mat3 de_a = cosine * Mat3::Identity() - xa * xb.transpose();
  const Mat3 de_b = -(cosine * Mat3::Identity() - xb * xa.transpose());
  for (int k = 0; k < 2; ++k) {
    const Vec3 y = a.axis(1 + k);
    rows.C(k) = y.dot(e);
    rows.jacobian[0].block<1, 3>(k, 3) = y.transpose() * de_a + y.cross(e).transpose();
    rows.jacobian[1].block<1, 3>(k, 3) = y.transpose() * de_b;
  }
  return rows;
}

void hinge_rows(const JointRowContext& c, BodyRowSink& sink) {
  const Joint& j = c.joint;
  if (c.wants_equality()) sink.take(alignment_rows(j, end_pose_a(c), end_pose_b(c)));
  if (c.wants_others() && j.limited) {
    const JointEndPose a = end_pose_a(c), b = end_pose_b(c);
    const Real phi = hinge_angle(a, b);
    if (phi < j.lower || phi > j.upper)
      sink.take(limit_row(j, a, b, phi, std::clamp(phi, j.lower, j.upper), -a.axis(0), true, JointSlot::limit, 0));
  }
  if (c.wants_others() && j.drive != DriveMode::none) {
    const JointEndPose a = end_pose_a(c), b = end_pose_b(c);
    const Real error = std::remainder(hinge_angle(a, b) - drive_target(j, c.drive_start, c.h), 2 * kPi);
    sink.take(drive_row(j, a, b, error, -a.axis(0), true));
  }
  if (c.wants_equality()) sink.take(attachment_rows(j, end_pose_a(c), end_pose_b(c)));
}

JointError hinge_error(const Joint& j, const JointEndPose& a, const JointEndPose& b) {
  JointError e{(a.anchor() - b.anchor()).norm(), std::asin(std::min(Real(1), a.axis(0).cross(b.axis(0)).norm()))};
  if (j.limited) e.angle = std::max(e.angle, excess(hinge_angle(a, b), j.lower, j.upper));
  return e;
}

}  // namespace

const JointTypeRules kHingeJoint{hinge_rows, [](const Joint&) { return 5; }, has_limit_or_drive, hinge_error,
                                 hinge_angle};

}  // namespace moreau
