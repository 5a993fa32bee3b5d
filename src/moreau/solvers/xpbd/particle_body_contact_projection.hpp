#pragma once
// XPBD's projection of particle-rigid body contacts (rows: constraints/particle_body_contact_rows.hpp),
// Mueller et al. 2020, "Detailed Rigid Body Simulation with XPBD", sec. 3.5 and 3.7.
//
// Every substep and iteration, per contact, in a fixed order (Gauss-Seidel, one thread):
//   normal   when C < 0, the positional correction of eq. 2-4 along n with
//            w = w_p + w_b(r, n), w_b = 1/m + (r x n)^T I^-1 (r x n); lambda_n accumulates
//   static   the tangential slip s_t (at the poses the normal correction left) is cancelled along
//   friction s_t/|s_t| when |s_t| / w_t < mu_s lambda_n                                  (eq. 5)
// Velocity pass, once per substep, per contact that pushed: dynamic friction and restitution with
// the laws of the particle contacts (particle_contact_projection.hpp), applied as an impulse
// between the particle and the body's material point (eq. 33).
#include "moreau/constraints/substep_start.hpp"

namespace moreau {

struct Model;
struct State;
struct RigidSubstepStart;

/// Clears the multipliers at the start of a substep.
void reset_particle_body_contacts(State& state);

/// Projection of all contacts in order; one thread; the friction slip measured from `start`, h the
/// substep (of a soft contact's spring).
void project_particle_body_contacts(const Model& model, State& state, const SubstepStart& start, Real h);

/// Velocity pass (dynamic friction, restitution) of the contacts that pushed this substep; one
/// thread. `velocity_before` and `bodies_before`: the particles' and bodies' velocities after prediction.
void particle_body_contact_velocities(const Model& model, State& state, const Vec3* velocity_before,
                                      const RigidSubstepStart& bodies_before, Real h);

}  // namespace moreau
