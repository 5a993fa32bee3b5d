#include "moreau/solvers/xpbd/project_fluid_density.hpp"

#include "moreau/fluids/density_constraint.hpp"
#include "moreau/fluids/fluid_scratch.hpp"
#include "moreau/math/target_clones.hpp"
#include "moreau/model/model.hpp"

namespace moreau {

void lay_out_pair_cache(const FluidState& fluid, FluidScratch& scratch) {
#pragma omp single
  {
    // Row i's pairs start at pair_offset[i], each row rounded up to whole chunks.
    const Index n = fluid.count;
    scratch.pair_offset.resize(n + 1);
    Index offset = 0;
    for (Index i = 0; i < n; ++i) {
      scratch.pair_offset[i] = offset;
      offset += (fluid.fluid_neighbors.count[i] + kPairChunk - 1) / kPairChunk * kPairChunk;
    }
    scratch.pair_offset[n] = offset;
    for (std::vector<Real>* v : {&scratch.pair_w, &scratch.pair_gx, &scratch.pair_gy, &scratch.pair_gz})
      if (v->size() < static_cast<std::size_t>(offset)) v->resize(offset + offset / 8);
  }
}

MOREAU_TARGET_CLONES
void project_fluid_density(const Model& model, FluidState& fluid, FluidScratch& scratch, Real h) {
  const FluidModel& fm = model.fluid;
  const Real V = fm.particle_volume;
  const Index n = fluid.count;
  const Real* w = fluid.inv_mass.data();
  const Real* mass = fluid.mass.data();
  const Index* phase = fluid.phase.data();
  const Real* solid_inv_mass = scratch.solid_inv_mass.data();

  // The multipliers' pass leaves every fluid pair's W_ij and grad W_ij in a cache that the
  // corrections' pass reads (positions do not change in between): the kernel is evaluated once per
  // pair and iteration. lay_out_pair_cache placed the rows for the current lists.
  const DensityPairCache cache{scratch.pair_offset.data(), scratch.pair_w.data(), scratch.pair_gx.data(),
                               scratch.pair_gy.data(), scratch.pair_gz.data()};

  // Multipliers.
#pragma omp for schedule(static)
  for (Index i = 0; i < n; ++i) {
    const auto [C, grad_i, wall_gradient, neighbor_term, solid_term] =
        evaluate_density_constraint(fm, fluid, solid_inv_mass, i, &cache);
    scratch.wall_gradient[i] = wall_gradient;
    const FluidPhase& ph = fm.phases[phase[i]];
    fluid.density[i] = ph.rest_density * (1 + C);
    // A solid particle (fluid_heat.hpp, w_i = 0) does not move, but its multiplier is the one it would
    // have as a liquid, so its liquid neighbours take their share of restoring its density.
    const Real w_i = w[i] > 0 ? w[i] : 1 / mass[i];
    const Real denominator = w_i * grad_i.squaredNorm() + V * V * neighbor_term + solid_term + ph.relaxation;
    scratch.lambda[i] = C > 0 ? -C / denominator : 0;
  }

  // Corrections (positions are only read here, so a second array keeps this Jacobi).
  // s_ij = -k (W_ij / W(dq h))^4 g_ref h (m_i + m_j) / 2 h_sub^2.
  const Real tensile = fm.tensile_k * fm.tensile_reference * h * h * 0.5, inv_w_dq = fm.tensile_inv_w_dq;
  const Real* lambda = scratch.lambda.data();
#pragma omp for schedule(static)
  for (Index i = 0; i < n; ++i) {
    const Real lambda_i = lambda[i], m_i = mass[i];
    alignas(64) Real dx[kPairChunk] = {}, dy[kPairChunk] = {}, dz[kPairChunk] = {};
    const Index* row = fluid.fluid_neighbors.row(i);
    const Index count = fluid.fluid_neighbors.count[i];
    for (Index begin = 0; begin < count; begin += kPairChunk) {
      // Lanes past the row's end hold its first neighbour (FixedStrideLists) and a zero gradient.
      const Index at = cache.offset[i] + begin;
      const Real *pw = cache.w + at, *pgx = cache.gx + at, *pgy = cache.gy + at, *pgz = cache.gz + at;
      alignas(64) Real lambda_j[kPairChunk], m_j[kPairChunk];
      gather_into(lambda_j, lambda, row + begin, 1, 0);
      gather_into(m_j, mass, row + begin, 1, 0);
      #pragma omp simd
      for (int k = 0; k < kPairChunk; ++k) {
        const Real t = pw[k] * inv_w_dq, t2 = t * t;
        const Real s_corr = -tensile * t2 * t2 * (m_i + m_j[k]);
        const Real coefficient = lambda_i + lambda_j[k] + s_corr;
        dx[k] += coefficient * pgx[k], dy[k] += coefficient * pgy[k], dz[k] += coefficient * pgz[k];
      }
    }
    Vec3 correction = V * Vec3(sum_lanes(dx), sum_lanes(dy), sum_lanes(dz));
    correction += lambda_i * scratch.wall_gradient[i];
    scratch.correction[i] = w[i] * correction;
  }
}

}  // namespace moreau
