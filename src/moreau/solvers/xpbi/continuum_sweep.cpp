#include "moreau/solvers/xpbi/continuum_sweep.hpp"

#include <cmath>

#include "moreau/continuum/plastic_flow.hpp"

namespace moreau {

namespace {

// Below this C (sqrt(Pa)) a particle is unstrained and its gradient direction undefined.
constexpr Real kUnstrained = 1e-12;

void project_elastoplastic(const Model& model, const State& state, const ContinuumNeighborhood& around,
                           const SubstepContext& ctx, Real& lambda, Index i) {
  const ContinuumModel& continuum = model.continuum;
  const ContinuumMaterial& material = continuum.materials[continuum.material[i]];
  const Mat3& Fn = state.continuum.deformation[i];
  const RotationSvd trial = rotation_svd((Mat3::Identity() + around.substep_deformation(continuum, ctx.x, ctx.x_start, i)) * Fn);
  const LameParameters lame = continuum_lame(material, state.continuum.plastic_volume[i]);
  const PlasticReturn returned = plastic_flow(material, lame, trial.sigma, ctx.h);
  const Real C = std::sqrt(2 * hencky_energy(lame, returned.sigma));
  if (!(C > kUnstrained)) return;
  // dC/dF (F^n)^T = P(F) (F^n)^T / C, P at the returned stretches.
  const Mat3 A = hencky_piola(lame, RotationSvd{trial.U, trial.V, returned.sigma}) * Fn.transpose() / C;
  const Index* list = around.neighbors.neighbors(i);
  const Index count = around.neighbors.count(i), first = around.neighbors.offset(i);
  const Index p = continuum.particle[i];
  // grad_b C = V_b A g_b, computed again where it is applied (cheaper than keeping it).
  auto grad = [&](Index k) -> Vec3 { return around.volume[list[k]] * (A * around.gradient[first + k]); };
  Vec3 grad_p = Vec3::Zero();
  Real w_grad_sq = 0;
  for (Index k = 0; k < count; ++k) {
    const Vec3 g = grad(k);
    grad_p -= g;
    w_grad_sq += ctx.inv_mass[continuum.particle[list[k]]] * g.squaredNorm();
  }
  w_grad_sq += ctx.inv_mass[p] * grad_p.squaredNorm();
  const Real dlambda = xpbd_delta_lambda(C, lambda, 1 / continuum.rest_volume[i], 0, ctx, w_grad_sq, 0);
  lambda += dlambda;
  for (Index k = 0; k < count; ++k) {
    const Index b = continuum.particle[list[k]];
    ctx.x[b] += (ctx.inv_mass[b] * dlambda) * grad(k);
  }
  ctx.x[p] += (ctx.inv_mass[p] * dlambda) * grad_p;
}

void separate_clumped(const Model& model, const ContinuumNeighborhood& around, const SubstepContext& ctx, Index i) {
  if (model.settings.xpbi.min_distance <= 0) return;
  const ContinuumModel& continuum = model.continuum;
  const Index* list = around.neighbors.neighbors(i);
  const Index count = around.neighbors.count(i);
  const Index p = continuum.particle[i];
  for (Index k = 0; k < count; ++k) {
    const Index b = continuum.particle[list[k]];
    const Real min_distance = std::min(around.clump_distance[i], around.clump_distance[list[k]]);
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
    const Index i = around.sweep_order[s];
    project_elastoplastic(model, state, around, ctx, lambda[i], i);
    separate_clumped(model, around, ctx, i);
  });
}

}  // namespace moreau
