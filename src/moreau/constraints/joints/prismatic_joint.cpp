// Prismatic (slider) joint: b slides relative to a along a's x axis without turning.
//   orientation  C = 2 s vec(f_a f_b^-1) = 0, 3 rows, angular compliance
//   sideways     C_k = y_k . d = 0 for y_k the two axes of a across the slide, d = p_a - p_b,
//                2 rows, compliance; y_k turns with a, so d(y_k . d) gains (y_k x d) . dtheta_a
//   slide        s = -(d . x_a): limits s in [lower, upper] (unilateral while violated, compliance)
//                and a drive to s_target or at a velocity with bounded force
// The slide's rows gain -(x_a x d) . dtheta_a from the axis turning with a. The direct tree
// solver takes none of these rows.
#include "moreau/constraints/joints/joint_row_blocks.hpp"
#include "moreau/constraints/joints/joint_type_rules.hpp"

namespace moreau {

namespace {

BodyRows sideways_rows(const Joint& j, const JointEndPose& a, const JointEndPose& b) {
  BodyRows rows = BodyRows::zero(j.bodies(), 2, JointSlot::position);
  rows.compliance.setConstant(j.compliance);
  const Vec3 d = a.anchor() - b.anchor();
  for (int k = 0; k < 2; ++k) {
    const Vec3 y = a.axis(1 + k);
    rows.C(k) = y.dot(d);
    rows.set_point_row(k, y, a.offset(), b.offset());
    rows.jacobian[0].block<1, 3>(k, 3) += y.cross(d).transpose();
  }
  return rows;
}

// The slide's own turning term on a row built along -x_a.
BodyRows with_axis_turning(BodyRows rows, const JointEndPose& a, const JointEndPose& b) {
  rows.jacobian[0].block<1, 3>(0, 3) -= a.axis(0).cross(a.anchor() - b.anchor()).transpose();
  return rows;
}

void prismatic_rows(const JointRowContext& c, BodyRowSink& sink) {
  const Joint& j = c.joint;
  if (c.wants_equality()) {
    sink.take(orientation_rows(j, end_pose_a(c), end_pose_b(c)));
    sink.take(sideways_rows(j, end_pose_a(c), end_pose_b(c)));
  }
  if (!c.wants_others()) return;
  if (j.limited) {
    const JointEndPose a = end_pose_a(c), b = end_pose_b(c);
    const Real slide = prismatic_slide(a, b);
    if (slide < j.lower || slide > j.upper)
      sink.take(with_axis_turning(limit_row(j, a, b, slide, std::clamp(slide, j.lower, j.upper), -a.axis(0), false,
                                            JointSlot::limit, j.compliance),
                                  a, b));
  }
  if (j.drive != DriveMode::none) {
    const JointEndPose a = end_pose_a(c), b = end_pose_b(c);
    const Real error = prismatic_slide(a, b) - drive_target(j, c.drive_start, c.h);
    sink.take(with_axis_turning(drive_row(j, a, b, error, -a.axis(0), false), a, b));
  }
}

JointError prismatic_error(const Joint& j, const JointEndPose& a, const JointEndPose& b) {
  const Vec3 x = a.axis(0), d = a.anchor() - b.anchor();
  JointError e{(d - d.dot(x) * x).norm(), orientation_error(a.frame(), b.frame()).norm()};
  if (j.limited) e.position = std::max(e.position, excess(-d.dot(x), j.lower, j.upper));
  return e;
}

}  // namespace

const JointTypeRules kPrismaticJoint{prismatic_rows, [](const Joint&) { return 0; }, has_limit_or_drive,
                                     prismatic_error, prismatic_slide};

}  // namespace moreau
