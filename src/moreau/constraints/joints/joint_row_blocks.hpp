#pragma once
// Row blocks that several joint types share (body_rows.hpp for the row shapes). Every block is
// evaluated at the poses given. The Jacobians are the exact derivatives of C, except that an
// angle about a hinge or twist axis is differentiated as a rotation about that axis (exact where
// the two ends' axes are aligned, which the alignment rows keep).
#include <algorithm>

#include "moreau/constraints/joints/joint_frames.hpp"

namespace moreau {

/// Attachment C = p_a - p_b (3 rows): dp = dx + dtheta x r = dx - [r]x dtheta.
BodyRows attachment_rows(const Joint& j, const JointEndPose& a, const JointEndPose& b);

/// The damper rows of a joint's `damping` (linear: three point rows along the world axes at the
/// anchors, whose rate is the anchors' relative velocity) or `angular_damping` (three rotation
/// rows about the world axes, the relative angular velocity). C = 0: they act on velocities only.
BodyRows damper_rows(const Joint& j, const JointEndPose& a, const JointEndPose& b, bool angular);

/// Gives compliant rows the joint's damping_time and, when the context has the substep start,
/// their `motion`: J times each end's motion since then (dx, and the rotation vector
/// 2 vec(q q_start^-1) of a body).
void set_damping(BodyRows& rows, const JointRowContext& c);

/// Fixed relative orientation C = 2 s vec(dq), dq = f_a f_b^-1 = (w, v), s = sign(w) (3 rows).
BodyRows orientation_rows(const Joint& j, const JointEndPose& a, const JointEndPose& b);

/// A drive's or a limit's single row on a coordinate whose value is `value` and whose target is
/// `target`: rotation rows about n for angles, point rows along n for slides. A limit row may only
/// push the coordinate back inside (unilateral); a drive row is bounded by the drive's force.
BodyRows limit_row(const Joint& j, const JointEndPose& a, const JointEndPose& b, Real value, Real target,
                   const Vec3& n, bool angular, int slot, Real compliance);
BodyRows drive_row(const Joint& j, const JointEndPose& a, const JointEndPose& b, Real error, const Vec3& n,
                   bool angular);

/// The drive's target coordinate this substep: the position target, or the start plus h times the
/// velocity target; inside the limits when the joint has them.
Real drive_target(const Joint& j, Real drive_start, Real h);

}  // namespace moreau
