#include "moreau/continuum/continuum_state.hpp"

#include "moreau/continuum/continuum_model.hpp"

namespace moreau {

ContinuumState make_continuum_state(const ContinuumModel& model) {
  ContinuumState s;
  s.deformation.assign(model.size(), Mat3::Identity());
  s.plastic_strain.assign(model.size(), 0);
  s.plastic_volume.assign(model.size(), 1);
  return s;
}

}  // namespace moreau
