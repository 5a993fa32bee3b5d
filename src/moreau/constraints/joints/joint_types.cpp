#include "moreau/constraints/joints/joint_type_rules.hpp"

namespace moreau {

namespace {

const JointTypeRules& rules(JointType type) {
  switch (type) {
    case JointType::fixed: return kFixedJoint;
    case JointType::spherical: return kSphericalJoint;
    case JointType::hinge: return kHingeJoint;
    case JointType::prismatic: return kPrismaticJoint;
    case JointType::distance: return kDistanceJoint;
    case JointType::rod: return kRodJoint;
  }
  return kSphericalJoint;
}

}  // namespace

void joint_rows(const JointRowContext& context, BodyRowSink& sink) { rules(context.joint.type).rows(context, sink); }

int direct_rows(const Joint& joint) { return rules(joint.type).direct_rows(joint); }

bool has_other_rows(const Joint& joint) { return rules(joint.type).has_other_rows(joint); }

JointError joint_error(const Joint& joint, const State& state) {
  return rules(joint.type).error(joint, end_pose(state, joint.ends[0]), end_pose(state, joint.ends[1]));
}

Real joint_coordinate(const Joint& joint, const State& state) {
  return rules(joint.type).coordinate(end_pose(state, joint.ends[0]), end_pose(state, joint.ends[1]));
}

}  // namespace moreau
