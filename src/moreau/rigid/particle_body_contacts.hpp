#pragma once
// Contacts between the particles of cloth and soft bodies and rigid bodies, two-way: a particle
// is a body without rotation (Mueller et al. 2020, sec. 3.7), so the contact is the body-body
// contact of sec. 3.5 with one end a point of radius g (the particle's collider gap).
//
// Once per step: particles sorted by x; each rigid body's world bounds, expanded by what either
// side can travel in the step (k dt (|v| + dt |g|), k = settings.contact_margin_factor, plus the
// body's turning |omega| R), select candidates whose distance to the shape is below g + that reach.
// Every substep and iteration, per contact, in a fixed order (Gauss-Seidel, one thread):
//   nearest surface point s of the body (body frame, point_query.hpp), n its outward normal (world)
//   normal   C = d(x_p) - g >= 0, d = (x_p - (x_b + q s)) . n; compliance 0
//            w = w_p + w_b(r, n), r = q s, w_b = 1/m + (r x n)^T I^-1 (r x n)      (eq. 2-4)
//   static   dp = (x_p - xbar_p) - ((x_b + q s) - (xbar_b + qbar s)), dp_t its tangential part;
//   friction cancelled (C = |dp_t| along dp_t) when |dlambda_t| < mu_s lambda_n            (eq. 5)
// Velocity pass, once per substep, per contact that pushed: dynamic friction and restitution with
// the same laws as the particle-collider contacts (contacts.hpp), applied as an impulse between
// the particle and the body's material point (eq. 33).
// Colliders are not rigid bodies here: particles meet them through collider contacts.
#include <array>
#include <vector>

#include "moreau/math/types.hpp"

namespace moreau {

struct Model;
struct State;

struct ParticleBodyContacts {
  std::vector<std::array<Index, 2>> pair;  // (body, particle), sorted
  std::vector<Real> lambda_normal;     // kg m, this substep
  std::vector<Vec3> normal;            // world, at the last projection
  std::vector<Vec3> offset;            // world, body surface point minus body centre, at the last projection
  std::vector<Real> static_friction, dynamic_friction, restitution;  // combined (means)
  std::vector<Index> by_x;             // detection scratch: particles sorted by x

  size_t size() const { return pair.size(); }
};

/// Gathers (particle, body) candidates for the coming step.
void detect_particle_body_contacts(const Model& model, State& state);

/// Clears the multipliers at the start of a substep.
void reset_particle_body_contacts(State& state);

/// Projection of all contacts in order; one thread.
void project_particle_body_contacts(const Model& model, State& state);

/// Velocity pass (dynamic friction, restitution) of the contacts that pushed this substep; one thread.
void particle_body_contact_velocities(const Model& model, State& state, Real h);

/// Contacts that pushed in the last substep and involve `object` (-1: any).
Index touching_particle_body_count(const Model& model, const State& state, Index object);

}  // namespace moreau
