#include "moreau/fluids/ambient_air.hpp"

#include <algorithm>
#include <cmath>

#include "moreau/model/model.hpp"

namespace moreau {

void apply_ambient_air_drag(const Model& model, FluidState& fluid, Real dt) {
  const FluidModel& fm = model.fluid;
  if (!fm.gas) return;
  const Index n = fluid.count;
#pragma omp for schedule(static)
  for (Index i = 0; i < n; ++i) {
    const FluidPhase& phase = fm.phases[fluid.phase[i]];
    if (!phase.gas || fluid.inv_mass[i] == 0) continue;
    const Real open = std::clamp(1 - fluid.density[i] / phase.rest_density, 0.0, 1.0);
    fluid.velocity[i] = phase.wind + (fluid.velocity[i] - phase.wind) * std::exp(-phase.gas_drag * open * dt);
  }
}

}  // namespace moreau
