#pragma once
// The solid side of a per-sample quantity: each particle of a coupled cloth, soft body or continuum
// gathers the vectors of the samples it carries, weighted by its barycentric weights,
//   g_k = sum_s b_sk v_s,
// over the particle -> sample table (solid_sampling.hpp) in its fixed order, so the sum does not
// depend on the thread count. The density coupling gathers the samples' reactions into position
// corrections (solid_coupling.hpp), the viscosity their viscous forces into velocity changes
// (fluid_viscosity.hpp).
#include "moreau/model/model.hpp"

namespace moreau {

/// Calls apply(k, w_k, g_k) for every particle k of a coupled solid with inverse mass w_k > 0.
/// Every thread; orphaned omp for.
template <class Apply>
void gather_to_solid_particles(const Model& model, const Vec3* per_sample, Apply&& apply) {
  const FluidSolidSamples& s = model.fluid.solid;
  const Index particles = static_cast<Index>(s.coupled_particle.size());
#pragma omp for schedule(static)
  for (Index q = 0; q < particles; ++q) {
    const Index p = s.coupled_particle[q];
    const Real w = model.particle_inv_mass[p];
    if (w <= 0) continue;
    Vec3 sum = Vec3::Zero();
    for (Index e = s.coupled_begin[q]; e < s.coupled_begin[q + 1]; ++e)
      sum += s.coupled_weight[e] * per_sample[s.coupled_sample[e]];
    apply(p, w, sum);
  }
}

}  // namespace moreau
