#pragma once
// How deep the contacts of the current step overlap at the current state: what the `penetration`
// probe reports and `moreau compare` sets side by side for two solvers.
//
// Over the contacts the step detected (its candidate lists, so contacts that formed after the
// detection are not seen until the next step), each contact's normal row value C (m; negative in
// penetration) is evaluated at the current positions:
//   rigid bodies (and the colliders they touch)  C = (p_a - p_b) . n   (constraints/contact_rows.hpp)
//   a particle and a rigid body                  C = phi_b(x_p) - g    (particle_body_contact_rows.hpp)
//   a particle and a collider                    C = phi_c(x_p) - g    (particle_contact_rows.hpp)
//   two particles                                C = |x_i - x_j| - (r_i + r_j)
// The depth is max(0, -C), the deepest over the contacts that involve the object.
#include "moreau/math/types.hpp"

namespace moreau {

struct Model;
struct State;

/// The deepest overlap (m, >= 0) of the contacts involving `object` (-1: every object).
Real deepest_penetration(const Model& model, const State& state, Index object);

}  // namespace moreau
