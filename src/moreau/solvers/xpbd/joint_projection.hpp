#pragma once
// XPBD on joints: the Gauss-Seidel pass over every joint's row blocks, the multipliers' reset at
// each substep, and the velocity pass for joint damping.
// Damping (Mueller et al. 2020, eq. 32): the anchors' relative velocity and the bodies' relative
// angular velocity lose the fraction min(c h, 1) per substep, c in 1/s.
#include "moreau/constraints/substep_start.hpp"

namespace moreau {

struct Model;
struct State;

/// Zeroes the joints' multipliers (start of a substep) and records each drive's starting
/// coordinate in `drive_start` (one per joint).
void reset_joints(const Model& model, State& state, Real* drive_start);

/// One Gauss-Seidel pass over all joints in scene order, block by block (each block evaluated at
/// the poses the previous ones left); the rows the direct tree solver took are skipped. One thread.
void project_joints(const Model& model, State& state, const Real* drive_start, const SubstepStart& start, Real h);

/// Joint damping (velocity pass).
void damp_joints(const Model& model, State& state, Real h);

}  // namespace moreau
