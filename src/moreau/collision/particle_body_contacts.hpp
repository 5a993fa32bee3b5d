#pragma once
// Detection of contacts between the particles of cloth and soft bodies and rigid bodies (rows:
// constraints/particle_body_contact_rows.hpp; XPBD's projection:
// solvers/xpbd/particle_body_contact_projection.hpp).
//
// Once per step: particles sorted by x; each rigid body's world bounds, expanded by what either
// side can travel in the step (k dt (|v| + dt |g|), k = settings.contact_margin_factor, plus the
// body's turning |omega| R), select candidates whose distance to the shape is below g + that reach
// (g the particle's collider gap). Colliders are not rigid bodies here: particles meet them
// through collider contacts.
#include <array>
#include <vector>

#include "moreau/constraints/compliant_contact.hpp"
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
  std::vector<Real> adhesion;          // N: the larger of the two sides' (glue on either holds; nmd)
  std::vector<ContactSpring> spring;   // a grain's viscoelastic contact (compliance 0: hard)
  std::vector<Index> by_x;             // detection scratch: particles sorted by x

  size_t size() const { return pair.size(); }
};

/// Gathers (particle, body) candidates for the coming step.
void detect_particle_body_contacts(const Model& model, State& state);

/// Contacts that pushed in the last substep and involve `object` (-1: any).
Index touching_particle_body_count(const Model& model, const State& state, Index object);

}  // namespace moreau
