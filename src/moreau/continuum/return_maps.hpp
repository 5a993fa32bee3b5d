#pragma once
// Return maps of the inelastic continua: the plastic flow that brings a trial elastic state back
// onto its yield surface, in the principal stretches sigma of the elastic deformation gradient
// F = U diag(sigma) V^T (the rotations stay; F = U diag(Z(sigma)) V^T after the map).
//
// With the St. Venant-Kirchhoff-Hencky law (hencky_elasticity.hpp) the Kirchhoff stress is
// tau_i = 2 mu eps_i + lambda tr eps in the Hencky strain eps = ln sigma, so its deviator is 2 mu
// times the strain's, eps^ = eps - (tr eps / 3) 1, and its trace (3 lambda + 2 mu) tr eps. The
// maps below flow along eps^ alone (a radial return in the deviatoric plane):
//
//   Drucker-Prager (Klar, Gast, Pradhana, Fu, Schroeder, Jiang, Teran 2016, "Drucker-Prager
//   elastoplasticity for sand animation", SIGGRAPH 2016), cohesionless sand of friction angle phi:
//     yield when |tau^| + alpha tr tau > 0, alpha = sqrt(2/3) 2 sin phi / (3 - sin phi), i.e.
//     dgamma = |eps^| + alpha (3 lambda + 2 mu) / (2 mu) tr eps > 0;
//     in tension (tr eps > 0) sand carries no stress: eps = 0 (the cone's tip);
//     otherwise eps -= dgamma eps^ / |eps^|, which keeps the volume (tr eps) and lands on the cone.
//   This alpha puts the cone through Mohr-Coulomb's in triaxial compression, where the largest
//   and smallest compressions a < b at yield satisfy (b - a) / (b + a) = sin phi.
//
//   von Mises (J2) plasticity, metal and plasticine of uniaxial yield stress sigma_Y: yield when
//   the von Mises stress sqrt(3/2) |tau^| exceeds sigma_Y, i.e.
//     dgamma = |eps^| - sqrt(2/3) sigma_Y / (2 mu) > 0;  eps -= dgamma eps^ / |eps^|,
//   volume preserving, back onto the cylinder. (XPBI's third-party descriptions write
//   sigma_Y / (2 mu), taking sigma_Y as the deviator's norm |tau^|; here sigma_Y is the stress at
//   which a bar pulled along its axis yields, as engineering tables give it.)
#include <cmath>

#include "moreau/continuum/hencky_elasticity.hpp"

namespace moreau {

/// A return map's result: the principal stretches after the flow and the plastic strain of the
/// flow, dgamma (the deviatoric Hencky strain removed; at the cone's tip |eps| before it).
struct PlasticReturn {
  Vec3 sigma;
  Real plastic_strain = 0;
  Real plastic_volume_factor = 1;  // J_p grows by this factor (snow; det of the flow)
};

/// alpha of the Drucker-Prager cone for friction angle phi (rad).
inline Real drucker_prager_alpha(Real friction_angle) {
  const Real s = std::sin(friction_angle);
  return std::sqrt(Real(2) / 3) * 2 * s / (3 - s);
}

/// `cohesion` (Pa, >= 0) moves the cone's tip from zero stress to an isotropic tension whose mean
/// Kirchhoff stress is the cohesion: the map acts on eps - s 1, s = cohesion / (3 lambda + 2 mu),
/// and s is added back.
inline PlasticReturn drucker_prager_return(const LameParameters& m, Real friction_angle, const Vec3& sigma,
                                           Real cohesion = 0) {
  const Real shift = cohesion / (3 * m.lambda + 2 * m.mu);
  const Vec3 eps = hencky_strain(sigma) - Vec3::Constant(shift);
  const Real trace = eps.sum();
  if (trace > 0) return {Vec3::Constant(std::exp(shift)), eps.norm()};  // beyond the tip: the tip's stress
  const Vec3 deviator = eps - (trace / 3) * Vec3::Ones();
  const Real norm = deviator.norm();
  const Real dgamma = norm + drucker_prager_alpha(friction_angle) * (3 * m.lambda + 2 * m.mu) / (2 * m.mu) * trace;
  if (dgamma <= 0 || norm <= 0) return {sigma, 0};  // inside the cone
  const Vec3 returned = eps - (dgamma / norm) * deviator + Vec3::Constant(shift);
  return {returned.array().exp().matrix(), dgamma};
}

inline PlasticReturn von_mises_return(const LameParameters& m, Real yield_stress, const Vec3& sigma) {
  const Vec3 eps = hencky_strain(sigma);
  const Vec3 deviator = eps - (eps.sum() / 3) * Vec3::Ones();
  const Real norm = deviator.norm();
  const Real dgamma = norm - std::sqrt(Real(2) / 3) * yield_stress / (2 * m.mu);
  if (dgamma <= 0) return {sigma, 0};
  const Vec3 returned = eps - (dgamma / norm) * deviator;
  return {returned.array().exp().matrix(), dgamma};
}

/// Herschel-Bulkley viscoplasticity (foam, cream, mud, paste; Bingham for flow index n = 1), the
/// overstress form of Yue, Smith, Batty, Chen, Zhang, Cao, Duhamel 2015 ("Continuum foam: a
/// material point method for shear-dependent flows", ACM TOG 34) written, like the maps above, in
/// the Hencky strain. In simple shear at rate gamma' the fluid carries tau = tau_y + K gamma'^n
/// once it flows; as a tensor law the deviatoric Kirchhoff stress has the norm
///   |tau^| = sqrt(2) (tau_y + K gamma'_eq^n),  gamma'_eq = sqrt(2) |D_p|,
/// where D_p is the plastic rate of deformation (simple shear: |tau^| = sqrt(2) tau, |D| =
/// gamma' / sqrt(2)). A substep h that removes dgamma along eps^ / |eps^| flows at |D_p| = dgamma
/// / h, and the returned stress 2 mu (|eps^_trial| - dgamma) must equal the flow stress:
///   f(dgamma) = 2 mu (N - dgamma) - sqrt(2) tau_y - sqrt(2) K (sqrt(2) dgamma / h)^n = 0,
/// N = |eps^_trial|. f decreases from f(0) > 0 (the trial state is beyond yield) to f <= 0 at
/// the rate-free return dgamma_0 = N - sqrt(2) tau_y / (2 mu) (von Mises with sigma_Y = sqrt(3)
/// tau_y, which K -> 0 recovers); for n = 1 the root is dgamma = 2 mu dgamma_0 / (2 mu + 2 K / h),
/// otherwise Newton's method safeguarded by bisection finds it. Volume is kept.
inline PlasticReturn herschel_bulkley_return(const LameParameters& m, Real shear_yield_stress, Real consistency,
                                             Real flow_index, Real h, const Vec3& sigma) {
  const Vec3 eps = hencky_strain(sigma);
  const Vec3 deviator = eps - (eps.sum() / 3) * Vec3::Ones();
  const Real norm = deviator.norm();
  const Real rate_free = norm - std::sqrt(Real(2)) * shear_yield_stress / (2 * m.mu);
  if (rate_free <= 0) return {sigma, 0};
  Real dgamma;
  if (flow_index == 1) {
    dgamma = 2 * m.mu * rate_free / (2 * m.mu + 2 * consistency / h);
  } else {
    const Real rate = std::sqrt(Real(2)) / h;  // equivalent shear rate per unit dgamma
    auto f = [&](Real g) { return 2 * m.mu * (rate_free - g) - std::sqrt(Real(2)) * consistency * std::pow(rate * g, flow_index); };
    Real lo = 0, hi = rate_free;
    dgamma = rate_free / 2;
    for (int iteration = 0; iteration < 60; ++iteration) {
      const Real value = f(dgamma);
      (value > 0 ? lo : hi) = dgamma;
      const Real slope = -2 * m.mu - std::sqrt(Real(2)) * consistency * flow_index * rate *
                                         std::pow(rate * dgamma, flow_index - 1);
      const Real newton = dgamma - value / slope;
      const Real next = newton > lo && newton < hi ? newton : (lo + hi) / 2;
      const bool converged = std::abs(next - dgamma) <= 1e-13 * rate_free;
      dgamma = next;
      if (converged) break;
    }
  }
  const Vec3 returned = eps - (dgamma / norm) * deviator;
  return {returned.array().exp().matrix(), dgamma};
}

/// A Maxwell fluid (silly putty, slime, polymer melts) of relaxation time lambda: a spring of
/// shear modulus mu in series with a dashpot of viscosity eta = mu lambda. The dashpot's flow is
/// D_p = tau^ / (2 eta), so at rest the deviatoric Kirchhoff stress relaxes as d tau^/dt =
/// -tau^ / lambda; in the Hencky strain, where tau^ = 2 mu eps^, the deviatoric strain relaxes alike
/// and the volume is kept. That is the Herschel-Bulkley flow above with tau_y = 0, n = 1 and
/// K = mu lambda, whose closed-form root takes the relaxation backward (implicit) Euler over h:
///   eps^ <- eps^_trial / (1 + h / lambda),   dgamma = |eps^_trial| h / (lambda + h).
/// Backward Euler keeps steady flow exact at any step: sheared at a rate gamma', a substep adds
/// h gamma' / 2 to the shear strain eps_xy and the map divides it by 1 + h / lambda, whose fixed
/// point eps_xy = lambda gamma' / 2 carries tau_xy = mu lambda gamma' = eta gamma' whatever
/// lambda / h (with lambda << h the stress reaches it within a step). Watched for much longer than
/// lambda the fluid is Newtonian with viscosity eta; in motions much quicker than lambda it is an
/// elastic solid. A held strain decays as (1 + h / lambda)^(-t / h), which tends to
/// exp(-t / lambda) as h / lambda -> 0. At small strains this is the upper-convected Maxwell model
/// (Oldroyd 1950), whose conformation tensor is the elastic left Cauchy-Green tensor F F^T here,
/// as in the conformation constraints of Barreiro, Garcia-Fernandez, Alduan, Otaduy 2017
/// ("Conformation constraints for efficient viscoelastic fluid simulation", SIGGRAPH Asia 2017);
/// its relaxation acts on ln(F F^T) / 2 instead of F F^T.
inline PlasticReturn maxwell_return(const LameParameters& m, Real relaxation_time, Real h, const Vec3& sigma) {
  return herschel_bulkley_return(m, 0, m.mu * relaxation_time, 1, h, sigma);
}

/// Snow after Stomakhin, Schroeder, Chai, Teran, Selle 2013 ("A material point method for snow
/// simulation", SIGGRAPH 2013): the stretches are clamped to [1 - theta_c, 1 + theta_s] and what
/// is clamped away becomes plastic; J_p grows by det(trial) / det(clamped). (The paper's elastic
/// law is fixed-corotated; here the clamp acts on the StVK-Hencky solid, and its hardening
/// exp(xi (1 - J_p)) scales that solid's Lame parameters: snow_hardened.)
inline PlasticReturn snow_return(Real critical_compression, Real critical_stretch, const Vec3& sigma) {
  const Vec3 clamped = sigma.cwiseMax(1 - critical_compression).cwiseMin(1 + critical_stretch);
  const Vec3 flow = hencky_strain(sigma) - hencky_strain(clamped);
  return {clamped, flow.norm(), sigma.prod() / clamped.prod()};
}

/// Snow's Lame parameters at plastic volume ratio J_p: compacted snow (J_p < 1) is stiffer.
inline LameParameters snow_hardened(const LameParameters& m, Real hardening, Real plastic_volume) {
  const Real scale = std::exp(hardening * (1 - plastic_volume));
  return {m.lambda * scale, m.mu * scale};
}

}  // namespace moreau
