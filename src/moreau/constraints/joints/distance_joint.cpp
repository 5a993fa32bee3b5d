// Distance joint: the anchors keep a distance |d| in [min, max] (Joint::lower, upper), d = p_a - p_b.
// One point row along n = d/|d|, C = |d| - target. With min = max it is an equality row the direct
// tree solver may take; a range is a unilateral row present only while |d| leaves it. The row is
// undefined at |d| = 0 and left out there.
#include "moreau/constraints/joints/joint_row_blocks.hpp"
#include "moreau/constraints/joints/joint_type_rules.hpp"

namespace moreau {

namespace {

bool is_rod(const Joint& j) { return j.lower == j.upper; }

void distance_rows(const JointRowContext& c, BodyRowSink& sink) {
  const Joint& j = c.joint;
  if (!(is_rod(j) ? c.wants_equality() : c.wants_others())) return;
  const JointEndPose a = end_pose_a(c), b = end_pose_b(c);
  const Vec3 d = a.anchor() - b.anchor();
  const Real len = d.norm();
  if (len <= 0) return;
  const Vec3 n = d / len;
  if (is_rod(j)) {
    BodyRows rows = BodyRows::zero(j.bodies(), 1, JointSlot::distance);
    rows.C(0) = len - j.lower;
    rows.compliance(0) = j.compliance;
    rows.set_point_row(0, n, a.offset(), b.offset());
    sink.take(rows);
  } else if (len < j.lower || len > j.upper) {
    sink.take(limit_row(j, a, b, len, std::clamp(len, j.lower, j.upper), n, false, JointSlot::distance, j.compliance));
  }
}

JointError distance_error(const Joint& j, const JointEndPose& a, const JointEndPose& b) {
  return {excess((a.anchor() - b.anchor()).norm(), j.lower, j.upper), 0};
}

}  // namespace

const JointTypeRules kDistanceJoint{distance_rows, [](const Joint& j) { return is_rod(j) ? 1 : 0; },
                                    [](const Joint& j) { return !is_rod(j); }, distance_error,
                                    no_coordinate};

}  // namespace moreau
