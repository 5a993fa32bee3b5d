#pragma once
// What each joint type file provides; joint_types.cpp lists the types.
#include "moreau/constraints/joints/joint_frames.hpp"

namespace moreau {

struct JointTypeRules {
  /// The row blocks at the context's poses, each evaluated just before it is handed on.
  void (*rows)(const JointRowContext& context, BodyRowSink& sink);
  /// Equality rows the direct tree solver may take (0: none).
  int (*direct_rows)(const Joint& joint);
  /// Whether it has rows besides the equality rows (limits, drives, a distance range).
  bool (*has_other_rows)(const Joint& joint);
  /// Positional (m) and angular (rad) violation.
  JointError (*error)(const Joint& joint, const JointEndPose& a, const JointEndPose& b);
  /// The joint's coordinate (hinge angle, slide) where it has one, else 0.
  Real (*coordinate)(const JointEndPose& a, const JointEndPose& b);
};

/// has_other_rows of the types with a coordinate (hinge, prismatic): a limit or a drive on it.
inline bool has_limit_or_drive(const Joint& joint) { return joint.limited || joint.drive != DriveMode::none; }

extern const JointTypeRules kFixedJoint, kSphericalJoint, kHingeJoint, kPrismaticJoint, kDistanceJoint, kRodJoint;

inline JointEndPose end_pose_a(const JointRowContext& c) { return end_pose(c.state, c.joint.ends[0]); }
inline JointEndPose end_pose_b(const JointRowContext& c) { return end_pose(c.state, c.joint.ends[1]); }
inline Real no_coordinate(const JointEndPose&, const JointEndPose&) { return 0; }

}  // namespace moreau
