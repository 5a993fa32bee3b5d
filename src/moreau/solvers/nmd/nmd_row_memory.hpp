#pragma once
// What the velocity-level solver (nmd) remembers of a step's impulses for the next step's warm
// start, where the particle families' multipliers (State::constraint_lambda) have another size.
// Part of the State: a checkpoint holds it, so a restarted run warm-starts as the uninterrupted one.
#include <vector>

#include "moreau/math/types.hpp"

namespace moreau {

struct NmdRowMemory {
  std::vector<Eigen::Matrix<Real, 6, 1>> neo_hookean;  // each Neo-Hookean tetrahedron's six Green-strain rows
  std::vector<Vec3> shape_match;                       // per shape-matching cluster entry (shape_match_rows.hpp)
};

}  // namespace moreau
