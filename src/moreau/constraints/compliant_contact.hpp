#pragma once
// A viscoelastic contact: the normal row of a contact as a spring of compliance alpha (m/N, the
// inverse of its stiffness k) beside a dashpot c (N s/m), pushing only (the linear spring-dashpot
// of DEM, Cundall and Strack 1979): the force is max(-(C + c alpha dC/dt) / alpha, 0) for the
// contact's gap C < 0. Grains at rest sink into each other by alpha times the load they carry.
//
// At the position level it is XPBD's damped compliant row (Macklin, Mueller, Chentanez 2016,
// eq. 26): with alpha~ = alpha / h^2 and gamma = alpha c / h (the relaxation time c alpha in
// substeps), dl = (-C - alpha~ l - gamma J dx) / ((1 + gamma) w + alpha~), J dx the normal motion
// of the sides over the substep, and the accumulated l kept at least its lower bound (0: the
// spring only pushes). At the velocity level it is SPOOK's row of compliance alpha and relaxation
// time c alpha (nmd_system.hpp). Hard contacts (alpha = 0) keep the plain projection dl = -C / w.
#include <algorithm>

#include "moreau/math/types.hpp"

namespace moreau {

struct ContactSpring {
  Real compliance = 0;  // m/N; 0: a hard contact
  Real damping = 0;     // N s/m

  bool soft() const { return compliance > 0; }
  /// c alpha, s: the time in which the dashpot relaxes the spring.
  Real relaxation_time() const { return compliance * damping; }
};

/// The increment of a soft contact's normal multiplier l (kg m, a force times h^2) at gap C (m),
/// with w the sides' summed inverse mass along the normal and `normal_motion` J dx (m) the
/// growth of the gap over the substep so far; l + dl stays at least `lower` (0, or minus a bond).
inline Real compliant_normal_increment(const ContactSpring& spring, Real C, Real normal_motion, Real lambda, Real w,
                                       Real lower, Real h) {
  const Real alpha_tilde = spring.compliance / (h * h);
  const Real gamma = spring.relaxation_time() / h;
  const Real dl = (-C - alpha_tilde * lambda - gamma * normal_motion) / ((1 + gamma) * w + alpha_tilde);
  return std::max(dl, lower - lambda);
}

/// The spring of a contact between two grains: the mean of the two objects' (as friction).
inline ContactSpring mean_spring(const ContactSpring& a, const ContactSpring& b) {
  return {0.5 * (a.compliance + b.compliance), 0.5 * (a.damping + b.damping)};
}

}  // namespace moreau
