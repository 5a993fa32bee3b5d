#include "moreau/solvers/xpbi/continuum_update.hpp"

#include "moreau/continuum/plastic_flow.hpp"

namespace moreau {

void finish_continuum_substep(const Model& model, State& state, const ContinuumNeighborhood& around,
                              const SubstepContext& ctx, ContinuumSubstepScratch& scratch) {
  const ContinuumModel& continuum = model.continuum;
  const Index n = continuum.size();
  const Real c = model.settings.xpbi.xsph;
#pragma omp for schedule(static)
  for (Index i = 0; i < n; ++i) scratch.velocity_gradient[i] = around.substep_deformation(continuum, ctx.x, ctx.x_start, i) * ctx.inv_h;
#pragma omp for schedule(static)
  for (Index i = 0; i < n; ++i) {
    const Index p = continuum.particle[i];
    const Index* list = around.neighbors.neighbors(i);
    const Index count = around.neighbors.count(i), first = around.neighbors.offset(i);
    Vec3 dv = Vec3::Zero();
    for (Index k = 0; k < count; ++k) {
      const Index j = list[k], b = continuum.particle[j];
      const Real weight = 0.5 * (around.volume[j] + model.particle_mass[b] / model.particle_mass[p] * around.volume[i]);
      const Vec3 linear = 0.5 * (scratch.velocity_gradient[i] + scratch.velocity_gradient[j]) * (around.start[j] - around.start[i]);
      dv += (weight * around.kernel[first + k]) * (state.velocity[b] - state.velocity[p] - linear);
    }
    scratch.smoothed[i] = state.velocity[p] + c * dv;
  }
#pragma omp for schedule(static)
  for (Index i = 0; i < n; ++i) {
    const Index p = continuum.particle[i];
    if (ctx.inv_mass[p] <= 0) continue;
    state.velocity[p] = scratch.smoothed[i];
    ctx.x[p] = ctx.x_start[p] + ctx.h * scratch.smoothed[i];
  }
  ContinuumState& deformation = state.continuum;
#pragma omp for schedule(static)
  for (Index i = 0; i < n; ++i) {
    const Mat3 G = around.substep_deformation(continuum, ctx.x, ctx.x_start, i);
    const ContinuumMaterial& material = continuum.materials[continuum.material[i]];
    const RotationSvd trial = rotation_svd((Mat3::Identity() + G) * deformation.deformation[i]);
    const PlasticReturn returned =
        plastic_flow(material, continuum_lame(material, deformation.plastic_volume[i]), trial.sigma, ctx.h);
    deformation.deformation[i] = trial.U * returned.sigma.asDiagonal() * trial.V.transpose();
    deformation.plastic_strain[i] += returned.plastic_strain;
    deformation.plastic_volume[i] *= returned.plastic_volume_factor;
  }
}

}  // namespace moreau
