#include "moreau/constraints/joints/joint_row_blocks.hpp"

#include <algorithm>

namespace moreau {

BodyRows attachment_rows(const Joint& j, const JointEndPose& a, const JointEndPose& b) {
  BodyRows rows = BodyRows::bilateral(j.bodies(), 3, JointSlot::position, j.compliance);
  rows.C = a.anchor() - b.anchor();
  const Vec3 ra = a.anchor() - a.center, rb = b.anchor() - b.center;
  rows.jacobian[0].block<3, 3>(0, 0) = Mat3::Identity();
  rows.jacobian[0].block<3, 3>(0, 3) = -cross_matrix(ra);
  rows.jacobian[1].block<3, 3>(0, 0) = -Mat3::Identity();
  rows.jacobian[1].block<3, 3>(0, 3) = cross_matrix(rb);
  return rows;
}

BodyRows damper_rows(const Joint& j, const JointEndPose& a, const JointEndPose& b, bool angular) {
  BodyRows rows = BodyRows::zero(j.bodies(), 3, JointSlot::position);
  for (int r = 0; r < 3; ++r) {
    if (angular)
      rows.set_rotation_row(r, Vec3::Unit(r));
    else
      rows.set_point_row(r, Vec3::Unit(r), a.offset(), b.offset());
  }
  return rows;
}

void set_damping(BodyRows& rows, const JointRowContext& c) {
  if (c.joint.damping_time <= 0) return;
  rows.damping_time = c.joint.damping_time;
  if (c.start == nullptr || c.start->body_position == nullptr) return;
  rows.motion = BodyRows::Vector::Zero(rows.size());
  for (int e = 0; e < 2; ++e) {
    const BodyEnd& end = rows.end[e];
    Eigen::Matrix<Real, 6, 1> move = Eigen::Matrix<Real, 6, 1>::Zero();
    if (end.kind == BodyEndKind::body) {
      move.head<3>() = c.state.rigid.position[end.index] - c.start->body_position[end.index];
      move.tail<3>() = orientation_error(c.state.rigid.orientation[end.index], c.start->body_orientation[end.index]);
    } else if (end.kind == BodyEndKind::particle) {
      move.head<3>() = c.state.position[end.index] - c.start->particle_position[end.index];
    }
    rows.motion += rows.jacobian[e] * move;
  }
}

// Turning a by dtheta adds 1/2 [dtheta, 0] dq, whose vector part is (w I - [v]x) dtheta; turning b
// subtracts 1/2 dq [dtheta, 0], vector part (w I + [v]x) dtheta.
BodyRows orientation_rows(const Joint& j, const JointEndPose& a, const JointEndPose& b) {
  BodyRows rows = BodyRows::zero(j.bodies(), 3, JointSlot::orientation);
  const Quat dq = a.frame() * b.frame().conjugate();
  const Real s = dq.w() >= 0 ? 1 : -1;
  rows.C = 2 * s * dq.vec();
  rows.compliance.setConstant(j.angular_compliance);
  rows.jacobian[0].block<3, 3>(0, 3) = s * (dq.w() * Mat3::Identity() - cross_matrix(dq.vec()));
  rows.jacobian[1].block<3, 3>(0, 3) = -s * (dq.w() * Mat3::Identity() + cross_matrix(dq.vec()));
  return rows;
}

BodyRows limit_row(const Joint& j, const JointEndPose& a, const JointEndPose& b, Real value, Real target,
                   const Vec3& n, bool angular, int slot, Real compliance) {
  BodyRows rows = BodyRows::zero(j.bodies(), 1, slot);
  rows.C(0) = value - target;
  rows.compliance(0) = compliance;
  if (angular)
    rows.set_rotation_row(0, n);
  else
    rows.set_point_row(0, n, a.offset(), b.offset());
  rows.make_unilateral(0, value < target);
  return rows;
}

BodyRows drive_row(const Joint& j, const JointEndPose& a, const JointEndPose& b, Real error, const Vec3& n,
                   bool angular) {
  BodyRows rows = BodyRows::zero(j.bodies(), 1, JointSlot::drive);
  rows.C(0) = error;
  rows.compliance(0) = j.drive_compliance;
  if (angular)
    rows.set_rotation_row(0, n);
  else
    rows.set_point_row(0, n, a.offset(), b.offset());
  if (j.drive == DriveMode::velocity) {
    rows.velocity_drive = true;
    rows.target_velocity = j.drive_target;
  }
  if (j.drive_max > 0) {
    rows.lower(0) = -j.drive_max;
    rows.upper(0) = j.drive_max;
  }
  return rows;
}

Real drive_target(const Joint& j, Real drive_start, Real h) {
  Real target = j.drive == DriveMode::position ? j.drive_target : drive_start + h * j.drive_target;
  if (j.limited) target = std::clamp(target, j.lower, j.upper);
  return target;
}

}  // namespace moreau
