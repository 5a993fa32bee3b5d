#include "moreau/rigid/rigid_bodies.hpp"

namespace moreau {

void RigidBodyState::resize(Index n) {
  position.resize(n);
  orientation.resize(n, Quat::Identity());
  velocity.resize(n);
  angular_velocity.resize(n);
}

Index RigidBodyModel::add(BodyDescription b) {
  const bool dynamic = b.motion == BodyMotion::dynamic;
  body_shape.push_back(std::move(b.shape));
  body_object.push_back(b.object);
  body_motion.push_back(b.motion);
  body_mass.push_back(b.mass);
  body_inv_mass.push_back(dynamic ? 1 / b.mass : 0);
  body_inertia.push_back(b.inertia);
  body_inv_inertia.push_back(dynamic ? Vec3(b.inertia.cwiseInverse()) : Vec3(Vec3::Zero()));
  body_frame_in_shape.push_back(b.frame_in_shape);
  body_center_in_shape.push_back(b.center_in_shape);
  body_static_friction.push_back(b.static_friction);
  body_dynamic_friction.push_back(b.dynamic_friction);
  body_restitution.push_back(b.restitution);
  body_adhesion.push_back(b.adhesion);
  initial_position.push_back(b.position);
  initial_orientation.push_back(b.orientation);
  initial_velocity.push_back(b.velocity);
  initial_angular_velocity.push_back(b.angular_velocity);
  return count() - 1;
}

}  // namespace moreau
