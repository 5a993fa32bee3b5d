#include "moreau/solvers/xpbd/project_fluid_density.hpp"

#include "moreau/fluids/density_constraint.hpp"
#include "moreau/fluids/fluid_scratch.hpp"
#include "moreau/math/target_clones.hpp"
#include "moreau/model/model.hpp"

namespace moreau {

MOREAU_TARGET_CLONES
void project_fluid_density(const Model& model, FluidState& fluid, FluidScratch& scratch, Real h) {
  const FluidModel& fm = model.fluid;
  const CubicSplineKernel kernel = fm.kernel;
  const Real V = fm.particle_volume, pad = 2 * kernel.h;
  const Index n = fluid.count;
  const Vec3* x = fluid.position.data();
  const Real* w = fluid.inv_mass.data();
  const Real* mass = fluid.mass.data();
  const Index* phase = fluid.phase.data();
  const Real* solid_inv_mass = scratch.solid_inv_mass.data();

  // Multipliers.
#pragma omp for schedule(static)
  for (Index i = 0; i < n; ++i) {
    const auto [C, grad_i, wall_gradient, neighbor_term, solid_term] = evaluate_density_constraint(fm, fluid, solid_inv_mass, i);
    scratch.wall_gradient[i] = wall_gradient;
    const FluidPhase& ph = fm.phases[phase[i]];
    fluid.density[i] = ph.rest_density * (1 + C);
    const Real denominator = w[i] * grad_i.squaredNorm() + V * V * neighbor_term + solid_term + ph.relaxation;
    scratch.lambda[i] = C > 0 ? -C / denominator : 0;
  }

  // Corrections (positions are only read here, so a second array keeps this Jacobi).
  // s_ij = -k (W_ij / W(dq h))^4 g_ref h (m_i + m_j) / 2 h_sub^2.
  const Real tensile = fm.tensile_k * fm.tensile_reference * h * h * 0.5, inv_w_dq = fm.tensile_inv_w_dq;
  const Real* lambda = scratch.lambda.data();
#pragma omp for schedule(static)
  for (Index i = 0; i < n; ++i) {
    const Vec3 xi = x[i];
    const Real lambda_i = lambda[i], m_i = mass[i];
    PairChunk chunk;
    alignas(64) Real dx[kPairChunk] = {}, dy[kPairChunk] = {}, dz[kPairChunk] = {};
    const Index* row = fluid.fluid_neighbors.row(i);
    const Index count = fluid.fluid_neighbors.count[i];
    for (Index begin = 0; begin < count; begin += kPairChunk) {
      chunk.load(xi, x, row, begin, count, pad, lambda, mass);
      chunk.evaluate(kernel);
      #pragma omp simd
      for (int k = 0; k < kPairChunk; ++k) {
        const Real t = chunk.w[k] * inv_w_dq, t2 = t * t;
        const Real s_corr = -tensile * t2 * t2 * (m_i + chunk.b[k]);
        const Real coefficient = (lambda_i + chunk.a[k] + s_corr) * chunk.g[k];
        dx[k] += coefficient * chunk.rx[k], dy[k] += coefficient * chunk.ry[k], dz[k] += coefficient * chunk.rz[k];
      }
    }
    Vec3 correction = V * Vec3(sum_lanes(dx), sum_lanes(dy), sum_lanes(dz));
    correction += lambda_i * scratch.wall_gradient[i];
    scratch.correction[i] = w[i] * correction;
  }
}

}  // namespace moreau
