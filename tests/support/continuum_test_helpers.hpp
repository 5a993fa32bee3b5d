#pragma once
// What the XPBI continuum tests measure on a scene's continua.
#include "moreau/continuum/continuum_stress.hpp"
#include "moreau/scene/scene.hpp"

namespace moreau::test {

/// sum_p V_p^0 tau_p (N m): the volume integral of the Cauchy stress over every continuum
/// particle, sum V sigma = sum V^0 J sigma, with tau the StVK-Hencky Kirchhoff stress of F.
inline Mat3 continuum_stress_integral(const Scene& scene) {
  const ContinuumModel& c = scene.model.continuum;
  const ContinuumState& s = scene.state.continuum;
  Mat3 total = Mat3::Zero();
  for (Index i = 0; i < c.size(); ++i) {
    const RotationSvd F = rotation_svd(s.deformation[i]);
    const LameParameters lame = continuum_lame(c.materials[c.material[i]], s.plastic_volume[i]);
    total += c.rest_volume[i] * (F.U * hencky_kirchhoff(lame, F.sigma).asDiagonal() * F.U.transpose());
  }
  return total;
}

}  // namespace moreau::test
