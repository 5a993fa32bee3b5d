#pragma once
// XPBD's projection of particle contacts (rows: constraints/particle_contact_rows.hpp), after
// Mueller et al. 2020, "Detailed Rigid Body Simulation with XPBD", sec. 3.5. Cloth and soft-body
// particles do not turn; grains turn as solid spheres, and their friction acts at the contact
// point, with rolling resistance (constraints/turning_contact.hpp derives the slip, the turn
// and the impulses).
//
// Position pass (every iteration), for a contact whose normal row is violated (C < 0):
//   dlambda_n = -C / w, w = w_i + w_j (w_i for a collider contact); lambda_n accumulates over the
//   substep's iterations; x_i += w_i dlambda_n n, x_j -= w_j dlambda_n n.
//   Static friction, all or nothing: the slip s (the friction rows' values) is cancelled, split
//   by inverse mass, when |s| / w < mu_s lambda_n.
//   A contact with a grain (a side that turns): Coulomb friction and rolling resistance at the
//   position level, their impulses P and L accumulated over the substep's iterations and bounded
//   there: the increments cancel the slip and the turn; L beyond mu_r R* lambda_n is cut back to
//   it, the slip then cancelled given it; P reaching mu_s lambda_n slides, cut back to
//   mu_k lambda_n (no further than sticking), the turn then cancelled within its bound.
//   Cohesion of two grains (a bond of strength F and reach g): the normal row also acts while
//   0 <= C < g, pulling the pair together, and lambda_n is bounded below by -F h^2: the bond
//   pulls with at most F and holds the pair together against a pull below F (the adhesion
//   constraint of Gascon, Zurdo and Otaduy 2010, with a reach). Within its reach the bond adds
//   F h^2 to lambda_n in the friction bounds, static and dynamic (Coulomb friction on the normal
//   force plus the bond's, as cohesive DEM contacts do), so bonded grains resist shear too.
// Velocity pass (once per substep, after v = (x - x_start)/h), on the contacts that pushed (and
// bonded pairs within reach, which get the dynamic friction only; a grain's contact gets the
// restitution only, its friction being all at the position level):
//   dynamic friction  dv = -v_t/|v_t| min(mu_k w lambda_n / h, |v_t|)
//     (the normal impulse of the substep is lambda_n / h; we use this dimensionally consistent
//      reading of Mueller 2020, eq. 30, whose f_n h mixes force and velocity)
//   restitution       dv = n (-v_n + max(-e vbar_n, 0)),  e = 0 when |v_n| <= 2 |g| h
//   each applied as an impulse split by inverse mass.
#include "moreau/math/types.hpp"
#include "moreau/solvers/xpbd/substep_context.hpp"

namespace moreau {

struct Model;
struct State;

/// Projections inside a substep; call inside an OpenMP parallel region. `substep_end_time` places
/// kinematic colliders.
void project_collider_contacts(const Model& model, State& state, const SubstepContext& s, Real substep_end_time);
void project_particle_contacts(const Model& model, State& state, const SubstepContext& s);

/// Relative-velocity change dv of one contact that pushed this substep (the two laws above): v_rel
/// and v_rel_before now and after prediction, n the normal, lambda_n the substep's normal
/// multiplier, w the summed inverse masses along n, g = |gravity| (the resting-speed cut-off).
Vec3 contact_velocity_change(const Vec3& v_rel, const Vec3& v_rel_before, const Vec3& n, Real lambda_n, Real w,
                             Real mu_k, Real e, Real h, Real g);

/// The restitution part of contact_velocity_change alone (along n).
Vec3 restitution_velocity_change(const Vec3& v_rel, const Vec3& v_rel_before, const Vec3& n, Real e, Real h, Real g);

/// The dynamic-friction part of contact_velocity_change alone.
Vec3 friction_velocity_change(const Vec3& v_rel, const Vec3& n, Real lambda_n, Real w, Real mu_k, Real h);

/// Velocity pass: dynamic friction and restitution of the contacts active in this substep;
/// `velocity_before` holds the particles' velocities after prediction.
void collider_contact_velocities(const Model& model, State& state, const Vec3* velocity_before, Real h);
void particle_contact_velocities(const Model& model, State& state, const Vec3* velocity_before, Real h);

}  // namespace moreau
