#pragma once
// The return map Z of a continuum particle's material (return_maps.hpp), and the elastic law it
// returns to (hencky_elasticity.hpp), chosen by the material's plastic model.
#include "moreau/continuum/continuum_model.hpp"
#include "moreau/continuum/return_maps.hpp"

namespace moreau {

/// Stretches below this are raised to it before the return map: a particle is never crushed to
/// less than 5 % of its length along any axis, where the logarithmic strain would diverge.
constexpr Real kMinContinuumStretch = 0.05;

/// The material's Lame parameters at plastic volume ratio J_p (only snow hardens).
inline LameParameters continuum_lame(const ContinuumMaterial& m, Real plastic_volume) {
  return m.plastic == PlasticModel::snow ? snow_hardened(m.lame, m.hardening, plastic_volume) : m.lame;
}

/// Z applied to trial principal stretches `sigma` reached over a step of h seconds (the rate
/// matters to Herschel-Bulkley and Maxwell), with Lame parameters `lame` (continuum_lame).
inline PlasticReturn plastic_flow(const ContinuumMaterial& m, const LameParameters& lame, Vec3 sigma, Real h) {
  sigma = sigma.cwiseMax(kMinContinuumStretch);
  switch (m.plastic) {
    case PlasticModel::drucker_prager: return drucker_prager_return(lame, m.friction_angle, sigma, m.cohesion);
    case PlasticModel::von_mises: return von_mises_return(lame, m.yield_stress, sigma);
    case PlasticModel::snow: return snow_return(m.critical_compression, m.critical_stretch, sigma);
    case PlasticModel::herschel_bulkley:
      return herschel_bulkley_return(lame, m.shear_yield_stress, m.consistency, m.flow_index, h, sigma);
    case PlasticModel::maxwell: return maxwell_return(lame, m.relaxation_time, h, sigma);
    case PlasticModel::none: break;
  }
  return {sigma, 0};
}

}  // namespace moreau
