#pragma once
// Constraint rows of a contact between a particle (of cloth or a soft body) and a rigid body:
// what every solver reads from one. A particle is a body without rotation (Mueller et al. 2020,
// "Detailed Rigid Body Simulation with XPBD", sec. 3.7), so this is the body-body contact of
// sec. 3.5 with one end a point of radius g (the particle's collider gap).
//
// With s the body's surface point nearest to the particle (body frame, point_query.hpp), n the
// outward normal there (world) and r = q s its world offset from the body's centre, point rows
// (body_rows.hpp) with ends (particle p, body b), compliance 0:
//   row 0   normal  C = (x_p - (x_b + q s)) . n - g >= 0: unilateral, the force f_n >= 0
//   rows 1,2 static C_k = s_t . t_k = 0, s_t the tangential part of the slip of the particle
//           friction against the body's material point over the substep,
//                   s = (x_p - xbar_p) - ((x_b + q s) - (xbar_b + qbar s)),
//           bounded by the friction cone |f_t| <= mu_s f_n
// A Gauss-Seidel solver evaluates the friction rows after projecting the normal row (at the poses
// it left), which particle_body_slip does on its own.
#include "moreau/constraints/body_rows.hpp"
#include "moreau/constraints/contact_rows.hpp"
#include "moreau/constraints/substep_start.hpp"
#include "moreau/collision/point_query.hpp"

namespace moreau {

struct Model;
struct State;

/// The nearest surface point of body b to world point x, with its world normal and offset.
struct ParticleBodyNormal {
  SurfacePoint surface;  // body frame: point s, normal, signed distance (m)
  Vec3 normal, offset;   // world: n and r = q s
};

ParticleBodyNormal nearest_on_body(const Model& model, const State& state, Index body, const Vec3& x);

/// The slip of particle p against body b's material point `local` (body frame) since `start`.
Vec3 particle_body_slip(const State& state, const SubstepStart& start, Index body, Index particle, const Vec3& local);

/// The contact's three rows and the friction coefficient mu_s of their cone.
struct ParticleBodyContactRows {
  BodyRows rows;
  Real static_friction = 0;
};

/// The rows at the current poses (friction along t1 = contact_tangent(n) and t2 = n x t1). A
/// contact not in penetration has zero rows unless `which` asks for every contact (speculative
/// rows of a velocity-level solver, C > 0).
ParticleBodyContactRows particle_body_rows(const Model& model, const State& state, const SubstepStart& start, Index body,
                                          Index particle, Real static_friction,
                                          ContactPoints which = ContactPoints::penetrating);

}  // namespace moreau
