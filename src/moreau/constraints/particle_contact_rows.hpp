#pragma once
// Constraint rows of a particle contact, with another particle or with a collider: what every
// solver reads from one.
//
// Non-penetration (Mueller et al. 2020, "Detailed Rigid Body Simulation with XPBD", sec. 3.5;
// particles are bodies without rotation), compliance 0, unilateral (the force f_n >= 0):
//   pair (i, j):  C = |x_i - x_j| - (r_i + r_j) >= 0   grad_xi C = n = (x_i - x_j)/|x_i - x_j|, grad_xj C = -n
//   collider:     C = phi(x) - g >= 0                  grad_x C = n, the collider's outward normal,
//                                                      g the particle's collider gap
// Static friction, two rows C_k = s . t_k = 0 (k = 1, 2) on the slip s, the relative tangential
// displacement over the substep (P_t = I - n n^T, x0 the substep's start, v_c the collider's
// velocity):
//   pair:      s = P_t [(x_i - x_i0) - (x_j - x_j0)],   grad_xi C_k = t_k, grad_xj C_k = -t_k
//   collider:  s = P_t [(x - x0) - h v_c],               grad_x C_k = t_k
// bounded by the friction cone |lambda_t| <= mu_s lambda_n, which couples the rows' bounds.
#include "moreau/constraints/constraint_rows.hpp"
#include "moreau/constraints/contact_rows.hpp"

namespace moreau {

/// The normal row of a contact: its value C (m) and its direction n (unit, or zero when the two
/// centres coincide and the row has no direction).
struct ContactNormal {
  Real C;
  Vec3 n;
};

[[gnu::always_inline]] inline ContactNormal pair_contact_normal(const Vec3& xi, const Vec3& xj, Real contact_distance) {
  const Vec3 d = xi - xj;
  const Real length = d.norm();
  if (length <= 0) return {-contact_distance, Vec3::Zero()};
  return {length - contact_distance, d / length};
}

/// The tangential part P_t d = d - (d . n) n of a displacement d.
[[gnu::always_inline]] inline Vec3 tangential_part(const Vec3& d, const Vec3& n) { return d - d.dot(n) * n; }

/// A contact's three rows over P particles: row 0 normal, rows 1 and 2 static friction along
/// t1 = contact_tangent(n) and t2 = n x t1. Row 0 has lower bound 0; rows 1 and 2 are bounded by
/// |lambda_t| <= static_friction * lambda_0 (a cone, so their fixed bounds stay infinite).
template <int P>
struct ParticleContactRows : RowBlock<P, 3> {
  Real static_friction = 0;  // mu_s
};

/// Rows of a contact between particles i and j, at positions x (substep start x_start); a
/// contact of coincident centres has no directions (zero gradients).
inline ParticleContactRows<2> pair_contact_rows(Index i, Index j, Real contact_distance, Real static_friction,
                                                const Vec3* x, const Vec3* x_start) {
  ParticleContactRows<2> rows;
  rows.particle = {i, j};
  rows.static_friction = static_friction;
  rows.lower[0] = 0;
  const ContactNormal normal = pair_contact_normal(x[i], x[j], contact_distance);
  rows.C[0] = normal.C;
  rows.gradient[0].setZero();
  rows.gradient[1].setZero();
  if (normal.n.isZero()) return rows;
  const Vec3 t1 = contact_tangent(normal.n), t2 = normal.n.cross(t1);
  const Vec3 slip = tangential_part((x[i] - x_start[i]) - (x[j] - x_start[j]), normal.n);
  rows.C[1] = slip.dot(t1);
  rows.C[2] = slip.dot(t2);
  rows.gradient[0] << normal.n.transpose(), t1.transpose(), t2.transpose();
  rows.gradient[1] = -rows.gradient[0];
  return rows;
}

/// Rows of a contact between particle p and a collider whose signed distance at p's position is
/// `distance` along outward normal n; `gap` is the particle's collider gap, `collider_motion` the
/// collider's displacement over the substep (h v_c).
inline ParticleContactRows<1> collider_contact_rows(Index p, Real distance, const Vec3& n, Real gap,
                                                    Real static_friction, const Vec3& collider_motion, const Vec3* x,
                                                    const Vec3* x_start) {
  ParticleContactRows<1> rows;
  rows.particle = {p};
  rows.static_friction = static_friction;
  rows.lower[0] = 0;
  rows.C[0] = distance - gap;
  const Vec3 t1 = contact_tangent(n), t2 = n.cross(t1);
  const Vec3 slip = tangential_part((x[p] - x_start[p]) - collider_motion, n);
  rows.C[1] = slip.dot(t1);
  rows.C[2] = slip.dot(t2);
  rows.gradient[0] << n.transpose(), t1.transpose(), t2.transpose();
  return rows;
}

}  // namespace moreau
