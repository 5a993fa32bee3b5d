#pragma once
// The stress a continuum particle carries, for output and probes: with F = U diag(sigma) V^T the
// principal Kirchhoff stresses are tau_i = 2 mu eps_i + lambda tr eps (hencky_elasticity.hpp), the
// Cauchy stresses tau_i / J with J = det F, and the von Mises stress sqrt(3/2) |dev sigma|.
#include <cmath>

#include "moreau/continuum/plastic_flow.hpp"

namespace moreau {

/// The principal Cauchy stresses (Pa; tension positive) of elastic deformation gradient F.
inline Vec3 principal_cauchy_stress(const ContinuumMaterial& m, Real plastic_volume, const Mat3& F) {
  const Vec3 sigma = rotation_svd(F).sigma.cwiseMax(kMinContinuumStretch);
  return hencky_kirchhoff(continuum_lame(m, plastic_volume), sigma) / sigma.prod();
}

/// sqrt(3/2) |dev s| of principal stresses s (Pa).
inline Real von_mises_stress(const Vec3& s) {
  const Vec3 deviator = s - Vec3::Constant(s.sum() / 3);
  return std::sqrt(1.5) * deviator.norm();
}

}  // namespace moreau
