#include "moreau/solvers/xpbi/continuum_update.hpp"

#include "moreau/continuum/packing_volume.hpp"
#include "moreau/continuum/plastic_flow.hpp"

namespace moreau {

namespace {

/// n_p = sum_b V_b^0 W(|x_b - x_p|), p included, at the substep's end (packing_volume.hpp); the
/// pairs are the substep's, found at its start.
Real packing(const ContinuumModel& continuum, const ContinuumNeighborhood& around, const WendlandKernel& kernel,
             const Vec3* x, Index i) {
  const Index* list = around.neighbors.neighbors(i);
  const Index count = around.neighbors.count(i);
  const Vec3& xp = x[continuum.particle[i]];
  Real sum = continuum.rest_volume[i] * kernel.value(0);
  for (Index k = 0; k < count; ++k) sum += continuum.rest_volume[list[k]] * kernel.value((x[continuum.particle[list[k]]] - xp).norm());
  return sum;
}

}  // namespace

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
  const WendlandKernel kernel(continuum.support());
  const Real lattice_sum = lattice_kernel_sum(kernel, continuum.spacing);
#pragma omp for schedule(static)
  for (Index i = 0; i < n; ++i) {
    const Mat3 G = around.substep_deformation(continuum, ctx.x, ctx.x_start, i);
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
    deformation.deformation[i] = packed_deformation(F, lattice_sum / packing(continuum, around, kernel, ctx.x, i),
                                                    deformation.plastic_volume[i]);
  }
}

}  // namespace moreau
