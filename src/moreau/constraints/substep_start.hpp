#pragma once
// The configuration a position-level friction row measures its slip from: particle positions and
// body poses at the start of the substep. A solver keeps them in its workspace and hands the rows
// this view; a velocity-level solver, whose friction rows act on velocities, has no slip to measure.
#include "moreau/math/pose.hpp"

namespace moreau {

struct SubstepStart {
  const Vec3* particle_position = nullptr;  // m, per model particle
  const Vec3* body_position = nullptr;      // m, per rigid body (centre of mass)
  const Quat* body_orientation = nullptr;   // per rigid body (principal frame -> world)

  Pose body_pose(Index b) const { return {body_position[b], body_orientation[b]}; }
};

}  // namespace moreau
