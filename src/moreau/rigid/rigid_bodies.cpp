#include "moreau/rigid/rigid_bodies.hpp"

namespace moreau {

void RigidBodyState::resize(Index n) {
  position.resize(n);
  orientation.resize(n, Quat::Identity());
  velocity.resize(n);
  angular_velocity.resize(n);
}

}  // namespace moreau
