#pragma once
// A viscoelastic contact: the normal row of a contact as a spring of compliance alpha (m/N, the
// inverse of its stiffness k) beside a dashpot c (N s/m), pushing only (the linear spring-dashpot
// of DEM, Cundall and Strack 1979): the force is max(-(C + c alpha dC/dt) / alpha, 0) for the
// contact's gap C < 0. Grains at rest sink into each other by alpha times the load they carry.
//
// At the position level it is XPBD's damped compliant row (Macklin, Mueller, Chentanez 2016,
// eq. 26) with the relaxation time c alpha, its accumulated multiplier kept at least 0 (the spring
// only pushes): compliant_normal_increment in solvers/xpbd/substep_context.hpp. At the velocity
// level it is SPOOK's row of compliance alpha and relaxation time c alpha (nmd_system.hpp). Hard
// contacts (alpha = 0) keep the plain projection dl = -C / w.
#include "moreau/math/types.hpp"

namespace moreau {

struct ContactSpring {
  Real compliance = 0;  // m/N; 0: a hard contact
  Real damping = 0;     // N s/m

  bool soft() const { return compliance > 0; }
  /// c alpha, s: the time in which the dashpot relaxes the spring.
  Real relaxation_time() const { return compliance * damping; }
};

/// The spring of a contact between two grains: the mean of the two objects' (as friction).
inline ContactSpring mean_spring(const ContactSpring& a, const ContactSpring& b) {
  return {0.5 * (a.compliance + b.compliance), 0.5 * (a.damping + b.damping)};
}

}  // namespace moreau
