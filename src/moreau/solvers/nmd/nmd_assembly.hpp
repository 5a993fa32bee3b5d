#pragma once
// Gathers every row of the constraint engine into an NMD system (nmd_system.hpp): the particle
// families' rows (constraints/particle_families.hpp), the joints' row blocks
// (constraints/joints/joint.hpp), shape matching's rows (shape_match_rows.hpp), and one contact block per contact point: particle-collider,
// particle-particle, rigid body-rigid body (every point of each manifold, separated ones as
// speculative contacts) and particle-rigid body (constraints/*contact_rows.hpp). The rows are
// the ones the position-level solver projects; here their Jacobians act on velocities. The one
// exception: a Neo-Hookean tetrahedron is handed on as six Green-strain rows with its tangent
// (constraints/neo_hookean_green_strain.hpp).
#include <vector>

#include "moreau/model/state.hpp"
#include "moreau/solvers/nmd/nmd_system.hpp"

namespace moreau {


/// Adds every block at the state's positions and velocities (`space` gathered from the state)
/// for a solve of step h ending at time `end_time`; the rigid contact points are filled on up to
/// `threads` threads (the same system for any count).
void assemble_nmd_system(const Model& model, State& state, const VelocitySpace& space, Real h, Real end_time,
                         NmdSystem& system, NmdRowMemory& memory, int threads = 1);

}  // namespace moreau
