#pragma once
// St. Venant-Kirchhoff elasticity in the Hencky (logarithmic) strain, the elastic law of the
// inelastic continua (XPBI, Yu et al. 2024; the same law as Klar et al. 2016's sand):
//
//   Psi(F) = mu tr(eps^2) + lambda/2 (tr eps)^2,   eps = ln Sigma,   F = U Sigma V^T,
//
// an energy per unit rest volume (J/m^3, Pa) of the principal stretches sigma_i alone (isotropic).
// Its derivatives:
//   dPsi/dsigma_i = (2 mu eps_i + lambda tr eps) / sigma_i,
//   P = dPsi/dF   = U diag(dPsi/dsigma) V^T                        (first Piola-Kirchhoff stress),
//   tau = P F^T   = U diag(2 mu eps_i + lambda tr eps) U^T          (Kirchhoff stress),
// so the Kirchhoff stress is linear in the Hencky strain, and its deviator is 2 mu times the
// strain's: the yield surfaces of the return maps (return_maps.hpp) are simple in eps.
// Defined for sigma_i > 0 (an inverted particle has no logarithmic strain).
#include <cmath>

#include "moreau/materials/hyperelastic.hpp"
#include "moreau/math/rotation_svd.hpp"

namespace moreau {

/// The Hencky strain eps_i = ln sigma_i of principal stretches sigma (all > 0).
inline Vec3 hencky_strain(const Vec3& sigma) { return sigma.array().log().matrix(); }

/// Psi (J/m^3) at principal stretches sigma.
inline Real hencky_energy(const LameParameters& m, const Vec3& sigma) {
  const Vec3 eps = hencky_strain(sigma);
  const Real trace = eps.sum();
  return m.mu * eps.squaredNorm() + 0.5 * m.lambda * trace * trace;
}

/// The principal Kirchhoff stresses 2 mu eps_i + lambda tr eps (Pa).
inline Vec3 hencky_kirchhoff(const LameParameters& m, const Vec3& sigma) {
  const Vec3 eps = hencky_strain(sigma);
  return (2 * m.mu * eps.array() + m.lambda * eps.sum()).matrix();
}

/// dPsi/dsigma_i (Pa).
inline Vec3 hencky_energy_gradient(const LameParameters& m, const Vec3& sigma) {
  return (hencky_kirchhoff(m, sigma).array() / sigma.array()).matrix();
}

/// P = dPsi/dF (Pa) of a decomposed F.
inline Mat3 hencky_piola(const LameParameters& m, const RotationSvd& F) {
  return F.U * hencky_energy_gradient(m, F.sigma).asDiagonal() * F.V.transpose();
}

}  // namespace moreau
