#include "moreau/fluids/ambient_air.hpp"

#include <algorithm>
#include <cmath>

#include "moreau/fluids/fluid_heat.hpp"
#include "moreau/model/model.hpp"

namespace moreau {

void apply_ambient_air(const Model& model, FluidState& fluid, Real dt) {
  const FluidModel& fm = model.fluid;
  if (!fm.gas) return;
  const Index n = fluid.count;
#pragma omp for schedule(static)
  for (Index i = 0; i < n; ++i) {
    const FluidPhase& phase = fm.phases[fluid.phase[i]];
    if (!phase.gas) continue;
    const Real open = std::clamp(1 - fluid.density[i] / phase.rest_density, 0.0, 1.0);
    if (phase.gas_mixing > 0) {
      const Real kept = std::exp(-phase.gas_mixing * open * dt);
      fluid.smoke[i] *= kept;
      if (phase.expansion != 0) {  // a buoyant gas: its heat mixes toward the air's T_ref too
        const Real ambient = fluid_enthalpy(phase, phase.reference_temperature);
        fluid.enthalpy[i] = ambient + (fluid.enthalpy[i] - ambient) * kept;
      }
    }
    if (fluid.inv_mass[i] == 0) continue;  // a frozen particle stays at rest, a held one on its course
    fluid.velocity[i] = phase.wind + (fluid.velocity[i] - phase.wind) * std::exp(-phase.gas_drag * open * dt);
  }
}

}  // namespace moreau
