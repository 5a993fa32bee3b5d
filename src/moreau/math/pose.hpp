#pragma once
// A rigid placement: a body-frame point r is at x + q r in the world.
#include "moreau/math/types.hpp"

namespace moreau {

struct Pose {
  Vec3 position = Vec3::Zero();
  Quat orientation = Quat::Identity();
  Vec3 to_world(const Vec3& local) const { return position + orientation * local; }
  Vec3 to_local(const Vec3& world) const { return orientation.conjugate() * (world - position); }
};

}  // namespace moreau
