#include "moreau/rigid/rigid_bodies.hpp"

namespace moreau {

void RigidBodyState::resize(Index n) {
  position.resize(n);
  orientation.resize(n, Quat::Identity());
  velocity.resize(n);
  angular_velocity.resize(n);
  start_position.resize(n);
  start_orientation.resize(n, Quat::Identity());
  velocity_before.resize(n, Vec3::Zero());
  angular_velocity_before.resize(n, Vec3::Zero());
}

}  // namespace moreau
