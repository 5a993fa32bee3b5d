#pragma once
// What a step changes in the inelastic continua, per continuum particle (continuum_model.hpp):
// the elastic deformation gradient and the plastic history.
#include <vector>

#include "moreau/math/types.hpp"

namespace moreau {

struct ContinuumModel;

struct ContinuumState {
  std::vector<Mat3> deformation;      // F, the elastic deformation gradient (I at rest)
  std::vector<Real> plastic_strain;   // the accumulated plastic (Hencky) strain, sum of the flows' dgamma
  std::vector<Real> plastic_volume;   // J_p, the plastic volume ratio (snow's hardening; 1 otherwise)

  Index size() const { return static_cast<Index>(deformation.size()); }
};

/// Every particle undeformed: F = I, no plastic strain, J_p = 1.
ContinuumState make_continuum_state(const ContinuumModel& model);

}  // namespace moreau
