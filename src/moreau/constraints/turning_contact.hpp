#pragma once
// Friction and rolling resistance of a contact whose sides may turn: grains are solid spheres
// (inverse inertia I^-1 = 5 / (2 m r^2)); other particles and colliders do not turn (I^-1 = 0).
//
// Side i touches side j along the unit normal n (from j to i); the contact point lies at the arm
// a_i = -r_i n from i's centre and a_j = +r_j n from j's (between two grains whose centres are d
// apart, r_i and r_j scaled by d / (r_i + r_j), so that a_j - a_i = d n and an impulse pair
// at the contact point exerts no net torque in that configuration). Over a substep the sides move by dx and
// turn by the rotation vector theta. The contact point slips by
//   s   = P_t (dx_i - dx_j) - (r_i theta_i + r_j theta_j) x n          (P_t = I - n n^T)
// and the sides turn on each other by rho = theta_i - theta_j: rolling (its tangential part) and
// twisting (its part along n), both resisted by rolling resistance.
// A tangential impulse p (kg m at the position level) on i, -p on j, and an angular impulse L
// (kg m^2) on i, -L on j, change them by (n x L keeps only L's tangential part: twisting does not
// make the contact point slip)
//   ds   = w_t p + c n x L,      w_t = w_i + w_j + r_i^2 I_i^-1 + r_j^2 I_j^-1
//   drho = -c n x p + k L,       c = r_i I_i^-1 - r_j I_j^-1,  k = I_i^-1 + I_j^-1
// (each side: dx = +-w p, dtheta = I^-1 (a x (+-p) +- L)). Sticking cancels both: with n x (n x u)
// = -u on the tangent plane,
//   p = (-s + (c/k) n x rho) / (w_t - c^2/k),   L = (-rho + c n x p) / k
// (the twist, along n, simply L_n = -rho_n / k), and w_t - c^2/k >= w_i + w_j > 0. Static
// friction holds while |p| < mu_s N and rolling resistance while |L| <= mu_r R* N (N the normal multiplier, R* = r_i r_j / (r_i + r_j) the
// contact's effective radius, r_i for a collider): the rolling torque of a contact is at most
// mu_r R* times its normal force (the constant rolling-resistance model of DEM, e.g. Ai, Chen,
// Rotter and Ooi 2011, model A).
#include "moreau/math/types.hpp"

namespace moreau {

/// One side of a contact: inverse mass (1/kg), inverse inertia (1/(kg m^2), 0: does not turn)
/// and the distance from its centre to the contact point (m).
struct ContactSide {
  Real w, inv_inertia, arm;
};

struct TurningContact {
  Real w_t;  // 1/kg: the slip's inverse mass
  Real c;    // 1/(kg m): the coupling of slip and roll
  Real k;    // 1/(kg m^2): the roll's inverse inertia
};

inline TurningContact turning_contact(const ContactSide& i, const ContactSide& j) {
  return {i.w + j.w + i.arm * i.arm * i.inv_inertia + j.arm * j.arm * j.inv_inertia,
          i.arm * i.inv_inertia - j.arm * j.inv_inertia, i.inv_inertia + j.inv_inertia};
}

/// The contact's effective radius R* (m): r_i r_j / (r_i + r_j), or r_i against a collider (r_j = 0).
inline Real effective_radius(Real r_i, Real r_j) { return r_j > 0 ? r_i * r_j / (r_i + r_j) : r_i; }

/// The impulses that cancel slip s and roll rho together (p tangential; L's tangential part
/// against rolling, its part along n, -rho_n / k, against twisting).
struct StickImpulses {
  Vec3 p, L;
};

inline StickImpulses stick_impulses(const TurningContact& t, const Vec3& n, const Vec3& slip, const Vec3& roll) {
  if (t.k <= 0) return {-slip / t.w_t, Vec3::Zero()};
  const Vec3 p = (-slip + (t.c / t.k) * n.cross(roll)) / (t.w_t - t.c * t.c / t.k);
  return {p, (-roll + t.c * n.cross(p)) / t.k};
}

/// The change of side i's rotation (or angular velocity) from impulses p and L; side j's is the
/// same formula with -p and -L.
inline Vec3 turn_change(const ContactSide& side, const Vec3& toward_center, const Vec3& p, const Vec3& L) {
  // a x p + L, the arm a = -arm * toward_center pointing from the centre to the contact point
  return side.inv_inertia * (-side.arm * toward_center.cross(p) + L);
}

}  // namespace moreau
