#include "moreau/solvers/xpbi/continuum_sweep.hpp"

#include <cmath>

#include "moreau/continuum/plastic_flow.hpp"

namespace moreau {

namespace {

// Below this C (sqrt(Pa)) a particle is unstrained and its gradient direction undefined.
constexpr Real kUnstrained = 1e-12;

// The particle at sweep position s.
void project_elastoplastic(const Model& model, const State& state, const ContinuumNeighborhood& around,
                           const SubstepContext& ctx, Real& lambda, Index s) {
  const ContinuumModel& continuum = model.continuum;
  const Index i = around.sweep_order[s];
  const ContinuumMaterial& material = continuum.materials[continuum.material[i]];
  const Mat3& Fn = state.continuum.deformation[i];
  const RotationSvd trial = rotation_svd((Mat3::Identity() + around.substep_deformation(continuum, ctx.x, ctx.x_start, s)) * Fn);
  const LameParameters lame = continuum_lame(material, state.continuum.plastic_volume[i]);
  const PlasticReturn returned = plastic_flow(material, lame, trial.sigma, ctx.h);
  const Real C = std::sqrt(2 * hencky_energy(lame, returned.sigma));
  if (!(C > kUnstrained)) return;
  // dC/dF (F^n)^T = P(F) (F^n)^T / C, P at the returned stretches.
  const Mat3 A = hencky_piola(lame, RotationSvd{trial.U, trial.V, returned.sigma}) * Fn.transpose() / C;
  // grad_b C = A V_b L_p grad W_b, grad_p C = -A S_p; sum_b w_b |grad_b C|^2 = tr(A M_p A^T).
  const Index p = continuum.particle[i];
  const Vec3 grad_p = -A * around.gradient_sum[s];
  const Real w_grad_sq = (A * around.gradient_metric[s]).cwiseProduct(A).sum() + ctx.inv_mass[p] * grad_p.squaredNorm();
  const Real dlambda = xpbd_delta_lambda(C, lambda, 1 / continuum.rest_volume[i], 0, ctx, w_grad_sq, 0);
  lambda += dlambda;
  const Mat3 step = dlambda * A;
  for (Index k = around.pair_begin[s]; k < around.pair_begin[s + 1]; ++k) {
    const Index b = around.neighbor_particle[k];
    ctx.x[b] += ctx.inv_mass[b] * (step * around.weighted_gradient[k]);
  }
  ctx.x[p] += (ctx.inv_mass[p] * dlambda) * grad_p;
}

// The particle at sweep position s.
void separate_clumped(const Model& model, const ContinuumNeighborhood& around, const SubstepContext& ctx, Index s) {
  if (model.settings.xpbi.min_distance <= 0) return;
  const Index i = around.sweep_order[s];
  const Index p = model.continuum.particle[i];
  for (Index k = around.pair_begin[s]; k < around.pair_begin[s + 1]; ++k) {
    const Index b = around.neighbor_particle[k];
    const Real min_distance = std::min(around.clump_distance[i], around.clump_distance[around.neighbor[k]]);
    const Vec3 d = ctx.x[p] - ctx.x[b];
    const Real distance2 = d.squaredNorm();
    if (distance2 >= min_distance * min_distance) continue;
    const Real w = ctx.inv_mass[p] + ctx.inv_mass[b], distance = std::sqrt(distance2);
    if (w <= 0 || distance <= 0) continue;  // two particles on one point have no direction to part in
    const Vec3 push = ((min_distance - distance) / (w * distance)) * d;
    ctx.x[p] += ctx.inv_mass[p] * push;
    ctx.x[b] -= ctx.inv_mass[b] * push;
  }
}

}  // namespace

void sweep_continuum(const Model& model, const State& state, const ContinuumNeighborhood& around,
                     const SubstepContext& ctx, std::vector<Real>& lambda) {
  for_each_by_tile(around.sweep_batches, [&](Index s) {
    project_elastoplastic(model, state, around, ctx, lambda[s], s);
    separate_clumped(model, around, ctx, s);
  });
}

}  // namespace moreau
