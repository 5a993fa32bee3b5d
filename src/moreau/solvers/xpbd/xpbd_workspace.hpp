#pragma once
// What the XPBD formulation keeps to itself between the stages of one step: buffers that are
// rewritten every substep or step and that nothing outside the solver reads. The State holds what
// a step changes and what a user, a probe or the next step reads (positions, velocities, the
// contact sets and the multipliers of the last substep); a checkpoint of the State is complete
// without this workspace.
#include <vector>

#include "moreau/collision/contacts.hpp"
#include "moreau/math/types.hpp"

namespace moreau {

struct Model;

struct XpbdWorkspace {
  std::vector<Vec3> substep_start;      // m, particle positions at the start of the current substep
  std::vector<Vec3> velocity_before;    // m/s, particle velocities after prediction (restitution)
  std::vector<Real> joint_drive_start;  // per joint: hinge angle (rad) or slide (m) at the substep start
  ContactScratch contact_scratch;       // reused buffers of particle-pair detection

  /// Sizes the buffers for `model` (nothing is reallocated when they already fit).
  void fit(const Model& model);
};

}  // namespace moreau
