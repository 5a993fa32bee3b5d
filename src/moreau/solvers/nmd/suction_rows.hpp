#pragma once
// Suction cups under the velocity-level formulation: each cup's seal against a collider or a rigid
// body, its air, and its cavity's volume row (constraints/suction_cavity.hpp for the physics).
#include "moreau/model/state.hpp"
#include "moreau/solvers/nmd/nmd_system.hpp"

namespace moreau {

/// Seals a cup whose every rim vertex is within its contact gap plus the seal gap of a collider or
/// a rigid body (the air inside at p0; the body then takes the row's force too), unseals one whose rim lifted further (the air back at p0), lets air
/// out of a sealed cavity squeezed below its air volume, and adds each sealed cavity's volume row
/// for the step of length h that starts at `start_time`; `in` is the block's scratch.
void add_suction_rows(const Model& model, State& state, const VelocitySpace& space, Real h, Real start_time,
                      NmdBlockInput& in, NmdSystem& system);

/// After the solve: each sealed cup's pressure difference, the force of its row.
void store_suction(const Model& model, State& state, Real h);

}  // namespace moreau
