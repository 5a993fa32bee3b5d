#include "moreau/fluids/density_constraint.hpp"

#include "moreau/model/model.hpp"

namespace moreau {

Real fluid_rest_denominator(const CubicSplineKernel& kernel, Real spacing, Real mass) {
  // A particle at the origin of a cubic lattice: D_rest = (V^2 / m) sum_j |grad W_ij|^2 (the sum
  // of the gradients vanishes by symmetry).
  const Real volume = spacing * spacing * spacing;
  const int reach = static_cast<int>(std::ceil(kernel.h / spacing));
  Real sum = 0;
  for (int a = -reach; a <= reach; ++a)
    for (int b = -reach; b <= reach; ++b)
      for (int c = -reach; c <= reach; ++c) {
        const Vec3 r = spacing * Vec3(a, b, c);
        const Real d = r.norm();
        if (d == 0 || d >= kernel.h) continue;
        sum += (kernel.gradient_factor(d) * r).squaredNorm();
      }
  return volume * volume / mass * sum;
}

Real fluid_density_constraint(const Model& model, const FluidState& fluid, Index i) {
  const FluidModel& fm = model.fluid;
  const CubicSplineKernel& kernel = fm.kernel;
  const Vec3 xi = fluid.position[i];
  Real fluid_sum = kernel.value(0), wall_sum = 0;
  const Index* row = fluid.fluid_neighbors.row(i);
  for (Index k = 0; k < fluid.fluid_neighbors.count[i]; ++k) fluid_sum += kernel.value((xi - fluid.position[row[k]]).norm());
  const Index* walls = fluid.boundary_neighbors.row(i);
  for (Index k = 0; k < fluid.boundary_neighbors.count[i]; ++k)
    wall_sum += fm.boundary.volume[walls[k]] * kernel.value((xi - fluid.boundary_position[walls[k]]).norm());
  return fm.particle_volume * fluid_sum + wall_sum - 1;
}

void project_fluid_density(const Model& model, FluidState& fluid, Real h) {
  const FluidModel& fm = model.fluid;
  const CubicSplineKernel kernel = fm.kernel;
  const Real V = fm.particle_volume;
  const Index n = fluid.count;
  const Vec3* x = fluid.position.data();
  const Vec3* xb = fluid.boundary_position.data();
  const Real* wall_volume = fm.boundary.volume.data();
  const Real* w = fluid.inv_mass.data();
  const Index* phase = fluid.phase.data();

  // Multipliers.
#pragma omp for schedule(static)
  for (Index i = 0; i < n; ++i) {
    const Vec3 xi = x[i];
    Real sum_w = kernel.sigma;  // W(0): the particle's own contribution
    Vec3 grad_i = Vec3::Zero();
    Real neighbor_term = 0;     // sum_j w_j |grad W_ij|^2
    const Index* row = fluid.fluid_neighbors.row(i);
    const Index count = fluid.fluid_neighbors.count[i];
    for (Index k = 0; k < count; ++k) {
      const Index j = row[k];
      const Vec3 r = xi - x[j];
      const Real r2 = r.squaredNorm();
      if (r2 >= kernel.h2) continue;  // in the list's skin
      Real wij, g;
      kernel.evaluate(r2, wij, g);
      sum_w += wij;
      const Vec3 grad = g * r;
      grad_i += grad;
      neighbor_term += w[j] * grad.squaredNorm();
    }
    Real C = V * sum_w - 1;
    grad_i *= V;
    const Index* walls = fluid.boundary_neighbors.row(i);
    const Index wall_count = fluid.boundary_neighbors.count[i];
    for (Index k = 0; k < wall_count; ++k) {
      const Index b = walls[k];
      const Vec3 r = xi - xb[b];
      const Real r2 = r.squaredNorm();
      if (r2 >= kernel.h2) continue;  // in the list's skin
      Real wib, g;
      kernel.evaluate(r2, wib, g);
      C += wall_volume[b] * wib;
      grad_i += (wall_volume[b] * g) * r;
    }
    const FluidPhase& ph = fm.phases[phase[i]];
    fluid.density[i] = ph.rest_density * (1 + C);
    const Real denominator = w[i] * grad_i.squaredNorm() + V * V * neighbor_term + ph.relaxation;
    fluid.lambda[i] = C > 0 ? -C / denominator : 0;
  }

  // Corrections (positions are only read here, so a second array keeps this Jacobi).
  const Real k_tensile = fm.tensile_k * h * h, inv_w_dq = fm.tensile_inv_w_dq;
  const Real* lambda = fluid.lambda.data();
#pragma omp for schedule(static)
  for (Index i = 0; i < n; ++i) {
    const Vec3 xi = x[i];
    const Real lambda_i = lambda[i];
    const Real half_scale_i = 0.5 * fm.phases[phase[i]].tensile_scale;
    Vec3 dx = Vec3::Zero();
    const Index* row = fluid.fluid_neighbors.row(i);
    const Index count = fluid.fluid_neighbors.count[i];
    for (Index k = 0; k < count; ++k) {
      const Index j = row[k];
      const Vec3 r = xi - x[j];
      const Real r2 = r.squaredNorm();
      if (r2 >= kernel.h2) continue;  // in the list's skin
      Real wij, g;
      kernel.evaluate(r2, wij, g);
      const Real t = wij * inv_w_dq, t2 = t * t;
      const Real s_corr = -k_tensile * t2 * t2 * (half_scale_i + 0.5 * fm.phases[phase[j]].tensile_scale);
      dx += ((lambda_i + lambda[j] + s_corr) * g) * r;
    }
    dx *= V;
    if (lambda_i != 0) {
      const Index* walls = fluid.boundary_neighbors.row(i);
      const Index wall_count = fluid.boundary_neighbors.count[i];
      for (Index k = 0; k < wall_count; ++k) {
        const Index b = walls[k];
        const Vec3 r = xi - xb[b];
        const Real r2 = r.squaredNorm();
        if (r2 >= kernel.h2) continue;
        Real wib, g;
        kernel.evaluate(r2, wib, g);
        dx += (lambda_i * wall_volume[b] * g) * r;
      }
    }
    fluid.correction[i] = w[i] * dx;
  }
}

}  // namespace moreau
