#pragma once
// XPBD on rigid contacts (Mueller et al. 2020, sec. 3.5-3.6): per substep the manifolds' rows
// (constraints/contact_rows.hpp) are projected as blocks (contact_blocks.hpp) in every iteration,
// then a velocity pass applies dynamic friction and restitution:
//   dynamic friction  dv = -v_t/|v_t| min(mu_k lambda_n/h (w_a + w_b), |v_t|)   (the friction
//                     impulse mu_k lambda_n/h: the dimensionally consistent reading of eq. 30)
//   restitution       dv = n (-v_n + max(-e min(vbar_n, v_n), 0)), e = 0 when |v_n| <= 2 |g| h
//                     (vbar_n before the solve; the current v_n too, so a pulse passes down a
//                     row of touching balls; rows of a manifold solved together)
#include "moreau/constraints/substep_start.hpp"

namespace moreau {

struct Model;
struct State;
struct RigidSubstepStart;

/// Clears the multipliers at the start of a substep.
void reset_rigid_contacts(State& state);

/// Projection of all manifolds (Gauss-Seidel over manifolds, in a fixed order); one thread.
void project_rigid_contacts(const Model& model, State& state, const SubstepStart& start);

/// End of a substep (after the projections): the slip each touching point kept is added to its
/// stuck slip while its manifold sticks; sliding or separation clears it.
void accumulate_stuck_slip(State& state, const SubstepStart& start);

/// Velocity pass of the manifolds in contact this substep; one thread. `before` holds the bodies'
/// velocities after prediction.
void rigid_contact_velocities(const Model& model, State& state, const RigidSubstepStart& before, Real h);

}  // namespace moreau
