// Fixed joint: the two frames keep their relative orientation and the anchors coincide.
//   orientation  C = 2 s vec(f_a f_b^-1) = 0    3 rows, angular compliance (rad/(N m))
//   attachment   C = p_a - p_b = 0               3 rows, compliance (m/N)
// Both are equality rows the direct tree solver may take (6 rows).
#include "moreau/constraints/joints/joint_row_blocks.hpp"
#include "moreau/constraints/joints/joint_type_rules.hpp"

namespace moreau {

namespace {

void fixed_rows(const JointRowContext& c, BodyRowSink& sink) {
  if (!c.wants_equality()) return;
  sink.take(orientation_rows(c.joint, end_pose_a(c), end_pose_b(c)));
  sink.take(attachment_rows(c.joint, end_pose_a(c), end_pose_b(c)));
}

JointError fixed_error(const Joint&, const JointEndPose& a, const JointEndPose& b) {
  return {(a.anchor() - b.anchor()).norm(), orientation_error(a.frame(), b.frame()).norm()};
}

}  // namespace

const JointTypeRules kFixedJoint{fixed_rows, [](const Joint&) { return 6; }, [](const Joint&) { return false; }, fixed_error, no_coordinate};

}  // namespace moreau
