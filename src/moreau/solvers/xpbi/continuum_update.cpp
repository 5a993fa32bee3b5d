#include "moreau/solvers/xpbi/continuum_update.hpp"

#include "moreau/continuum/packing_volume.hpp"
#include "moreau/continuum/plastic_flow.hpp"

namespace moreau {

namespace {

/// n_p = sum_b V_b^0 W(|x_b - x_p|), p included, at the substep's end (packing_volume.hpp), for
/// the particle at sweep position s; the pairs are the substep's, found at its start.
Real packing(const ContinuumModel& continuum, const ContinuumNeighborhood& around, const WendlandKernel& kernel,
             const Vec3* x, Index s) {
  const Index i = around.sweep_order[s];
  const Vec3& xp = x[continuum.particle[i]];
  Real sum = continuum.rest_volume[i] * kernel.value(0);
  for (Index k = around.pair_begin[s]; k < around.pair_begin[s + 1]; ++k)
    sum += continuum.rest_volume[around.neighbor[k]] * kernel.value((x[around.neighbor_particle[k]] - xp).norm());
  return sum;
}

}  // namespace

void finish_continuum_substep(const Model& model, State& state, const ContinuumNeighborhood& around,
                              const SubstepContext& ctx, ContinuumSubstepScratch& scratch) {
  const ContinuumModel& continuum = model.continuum;
  const Index n = around.live_count();
  const Real c = model.settings.xpbi.xsph;
  // The passes below go through the particles in the sweep's order, in which the pairs are laid out.
#pragma omp for schedule(static)
  for (Index s = 0; s < n; ++s)
    scratch.velocity_gradient[around.sweep_order[s]] = around.substep_deformation(continuum, ctx.x, ctx.x_start, s) * ctx.inv_h;
#pragma omp for schedule(static)
  for (Index s = 0; s < n; ++s) {
    const Index i = around.sweep_order[s], p = continuum.particle[i];
    Vec3 dv = Vec3::Zero();
    for (Index k = around.pair_begin[s]; k < around.pair_begin[s + 1]; ++k) {
      const Index j = around.neighbor[k], b = around.neighbor_particle[k];
      const Real weight = 0.5 * (around.volume[j] + model.particle_mass[b] / model.particle_mass[p] * around.volume[i]);
      const Vec3 linear = 0.5 * (scratch.velocity_gradient[i] + scratch.velocity_gradient[j]) * (around.start[j] - around.start[i]);
      dv += (weight * around.kernel[k]) * (state.velocity[b] - state.velocity[p] - linear);
    }
    scratch.smoothed[i] = state.velocity[p] + c * dv;
  }
#pragma omp for schedule(static)
  for (Index s = 0; s < n; ++s) {
    const Index i = around.sweep_order[s], p = continuum.particle[i];
    if (ctx.inv_mass[p] <= 0) continue;  // pinned, or held in an emitter's nozzle
    state.velocity[p] = scratch.smoothed[i];
    ctx.x[p] = ctx.x_start[p] + ctx.h * scratch.smoothed[i];
  }
  ContinuumState& deformation = state.continuum;
  const WendlandKernel kernel(continuum.support());
  const Real lattice_sum = lattice_kernel_sum(kernel, continuum.spacing);
#pragma omp for schedule(static)
  for (Index s = 0; s < n; ++s) {
    const Index i = around.sweep_order[s];
    const Mat3 G = around.substep_deformation(continuum, ctx.x, ctx.x_start, s);
    const ContinuumMaterial& material = continuum.materials[continuum.material[i]];
    const RotationSvd trial = rotation_svd((Mat3::Identity() + G) * deformation.deformation[i]);
    const PlasticReturn returned =
        plastic_flow(material, continuum_lame(material, deformation.plastic_volume[i]), trial.sigma, ctx.h);
    deformation.plastic_strain[i] += returned.plastic_strain;
    deformation.plastic_volume[i] *= returned.plastic_volume_factor;
    const Mat3 F = trial.U * returned.sigma.asDiagonal() * trial.V.transpose();
    if (!model.settings.xpbi.packing_volume) {
      deformation.deformation[i] = F;
      continue;
    }
    deformation.deformation[i] = packed_deformation(F, lattice_sum / packing(continuum, around, kernel, ctx.x, s),
                                                    deformation.plastic_volume[i]);
  }
}

}  // namespace moreau
