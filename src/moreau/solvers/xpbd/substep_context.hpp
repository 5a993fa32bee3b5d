#pragma once
// The XPBD multiplier update shared by every constraint family.
//
// Macklin, Mueller, Chentanez 2016 (XPBD), eq. (18) with damping, eq. (26):
//   dlambda = (-C - alpha~ lambda - gamma gradC (x - x_start)) / ((1 + gamma) gradC W gradC^T + alpha~)
//   alpha~ = alpha / h^2,   gamma = alpha~ beta~ / h,   beta~ = h^2 beta.
// moreau states damping as a time constant tau (s) of stiffness-proportional (Kelvin-Voigt)
// damping, beta = tau / alpha, so that gamma = tau / h for every constraint, rigid or compliant.
#include <algorithm>

#include "moreau/constraints/compliant_contact.hpp"
#include "moreau/math/types.hpp"

namespace moreau {

/// What a projection needs from the current substep.
struct SubstepContext {
  Vec3* x;                    // positions being corrected, m
  const Vec3* x_start;        // positions at the start of the substep, m
  const Real* inv_mass;       // 1/kg (0: the particle does not move)
  Real h;                     // substep, s
  Real inv_h = 1 / h;         // 1/s
  Real inv_h2 = inv_h * inv_h;  // 1/s^2
  Vec3* turn = nullptr;               // rad: grains' rotation vectors over the substep so far (h omega + corrections)
  const Real* inv_inertia = nullptr;  // 1/(kg m^2) (0: the particle does not turn)
};

/// Scalar XPBD update for a substep of 1/inv_h s. `w_grad_sq` = sum_i w_i |grad_i C|^2;
/// `grad_dot_dx` = sum_i grad_i C . (x_i - x_start_i) (only read when damping_time > 0).
inline Real xpbd_delta_lambda(Real C, Real lambda, Real compliance, Real damping_time, Real inv_h, Real inv_h2,
                              Real w_grad_sq, Real grad_dot_dx) {
  const Real alpha_tilde = compliance * inv_h2;
  const Real gamma = damping_time * inv_h;
  const Real denominator = (1 + gamma) * w_grad_sq + alpha_tilde;
  if (denominator <= 0) return 0;
  return (-C - alpha_tilde * lambda - gamma * grad_dot_dx) / denominator;
}

/// The same in the current substep.
inline Real xpbd_delta_lambda(Real C, Real lambda, Real compliance, Real damping_time, const SubstepContext& s,
                              Real w_grad_sq, Real grad_dot_dx) {
  return xpbd_delta_lambda(C, lambda, compliance, damping_time, s.inv_h, s.inv_h2, w_grad_sq, grad_dot_dx);
}

/// A soft contact's normal row (constraints/compliant_contact.hpp): the damped compliant update of
/// its multiplier l (kg m) at gap C with the relaxation time c alpha, `normal_motion` J dx the
/// gap's growth over the substep so far, w the sides' summed inverse mass along the normal; l + dl
/// stays at least `lower` (0: the spring only pushes; minus a bond's F h^2).
inline Real compliant_normal_increment(const ContactSpring& spring, Real C, Real normal_motion, Real lambda, Real w,
                                       Real lower, Real h) {
  const Real inv_h = 1 / h;
  return std::max(xpbd_delta_lambda(C, lambda, spring.compliance, spring.relaxation_time(), inv_h, inv_h * inv_h, w,
                                    normal_motion),
                  lower - lambda);
}

}  // namespace moreau
