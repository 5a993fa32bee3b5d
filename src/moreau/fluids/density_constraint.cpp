#include "moreau/fluids/density_constraint.hpp"

#include "moreau/fluids/pair_chunks.hpp"
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

__attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
void project_fluid_density(const Model& model, FluidState& fluid, Real h) {
  const FluidModel& fm = model.fluid;
  const CubicSplineKernel kernel = fm.kernel;
  const Real V = fm.particle_volume, pad = 2 * kernel.h;
  const Index n = fluid.count;
  const Vec3* x = fluid.position.data();
  const Vec3* xb = fluid.boundary_position.data();
  const Real* wall_volume = fm.boundary.volume.data();
  const Vec3* xs = fluid.solid_position.data();
  const Real* solid_volume = fm.solid.volume.data();
  const Real* solid_inv_mass = fluid.solid_inv_mass.data();
  const Real* w = fluid.inv_mass.data();
  const Real* mass = fluid.mass.data();
  const Index* phase = fluid.phase.data();

  // Multipliers.
#pragma omp for schedule(static)
  for (Index i = 0; i < n; ++i) {
    const Vec3 xi = x[i];
    PairChunk chunk;
    alignas(64) Real sum_w[kPairChunk] = {}, gx[kPairChunk] = {}, gy[kPairChunk] = {}, gz[kPairChunk] = {},
                     w_grad2[kPairChunk] = {};
    const Index* row = fluid.fluid_neighbors.row(i);
    const Index count = fluid.fluid_neighbors.count[i];
    for (Index begin = 0; begin < count; begin += kPairChunk) {
      chunk.load(xi, x, row, begin, count, pad, w);
      chunk.evaluate(kernel);
      #pragma omp simd
      for (int k = 0; k < kPairChunk; ++k) {
        const Real Gx = chunk.g[k] * chunk.rx[k], Gy = chunk.g[k] * chunk.ry[k], Gz = chunk.g[k] * chunk.rz[k];
        sum_w[k] += chunk.w[k];
        gx[k] += Gx, gy[k] += Gy, gz[k] += Gz;
        w_grad2[k] += chunk.a[k] * (Gx * Gx + Gy * Gy + Gz * Gz);  // w_j |grad W_ij|^2
      }
    }
    Real C = V * (kernel.sigma + sum_lanes(sum_w)) - 1;  // sigma = W(0): the particle itself
    Vec3 grad_i = V * Vec3(sum_lanes(gx), sum_lanes(gy), sum_lanes(gz));
    const Real neighbor_term = sum_lanes(w_grad2);

    // Walls: C += sum_b V_b W_ib, grad_i += sum_b V_b grad W_ib (kept for the correction pass:
    // positions do not change between the two passes).
    const Index* walls = fluid.boundary_neighbors.row(i);
    const Index wall_count = fluid.boundary_neighbors.count[i];
    Vec3 wall_gradient = Vec3::Zero();
    if (wall_count > 0) {
      alignas(64) Real wall_w[kPairChunk] = {}, wx[kPairChunk] = {}, wy[kPairChunk] = {}, wz[kPairChunk] = {};
      for (Index begin = 0; begin < wall_count; begin += kPairChunk) {
        chunk.load(xi, xb, walls, begin, wall_count, pad, wall_volume);
        chunk.evaluate(kernel);
        #pragma omp simd
        for (int k = 0; k < kPairChunk; ++k) {
          const Real vg = chunk.a[k] * chunk.g[k];
          wall_w[k] += chunk.a[k] * chunk.w[k];
          wx[k] += vg * chunk.rx[k], wy[k] += vg * chunk.ry[k], wz[k] += vg * chunk.rz[k];
        }
      }
      C += sum_lanes(wall_w);
      wall_gradient = Vec3(sum_lanes(wx), sum_lanes(wy), sum_lanes(wz));
      grad_i += wall_gradient;
    }
    // Cloth and soft-body samples (solid_coupling.hpp): like walls, and they move, so each adds
    // w_s V_s^2 |grad W_is|^2 to the denominator.
    Real solid_term = 0;
    const Index solid_count = fluid.solid_neighbors.count[i];
    if (solid_count > 0) {
      const Index* solids = fluid.solid_neighbors.row(i);
      alignas(64) Real solid_w[kPairChunk] = {}, sx[kPairChunk] = {}, sy[kPairChunk] = {}, sz[kPairChunk] = {},
                       s_grad2[kPairChunk] = {};
      for (Index begin = 0; begin < solid_count; begin += kPairChunk) {
        chunk.load(xi, xs, solids, begin, solid_count, pad, solid_volume, solid_inv_mass);
        chunk.evaluate(kernel);
        #pragma omp simd
        for (int k = 0; k < kPairChunk; ++k) {
          const Real vg = chunk.a[k] * chunk.g[k];
          const Real Gx = vg * chunk.rx[k], Gy = vg * chunk.ry[k], Gz = vg * chunk.rz[k];
          solid_w[k] += chunk.a[k] * chunk.w[k];
          sx[k] += Gx, sy[k] += Gy, sz[k] += Gz;
          s_grad2[k] += chunk.b[k] * (Gx * Gx + Gy * Gy + Gz * Gz);
        }
      }
      C += sum_lanes(solid_w);
      const Vec3 solid_gradient(sum_lanes(sx), sum_lanes(sy), sum_lanes(sz));
      wall_gradient += solid_gradient;
      grad_i += solid_gradient;
      solid_term = sum_lanes(s_grad2);
    }
    fluid.wall_gradient[i] = wall_gradient;
    const FluidPhase& ph = fm.phases[phase[i]];
    fluid.density[i] = ph.rest_density * (1 + C);
    const Real denominator = w[i] * grad_i.squaredNorm() + V * V * neighbor_term + solid_term + ph.relaxation;
    fluid.lambda[i] = C > 0 ? -C / denominator : 0;
  }

  // Corrections (positions are only read here, so a second array keeps this Jacobi).
  // s_ij = -k (W_ij / W(dq h))^4 g_ref h (m_i + m_j) / 2 h_sub^2.
  const Real tensile = fm.tensile_k * fm.tensile_reference * h * h * 0.5, inv_w_dq = fm.tensile_inv_w_dq;
  const Real* lambda = fluid.lambda.data();
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
    correction += lambda_i * fluid.wall_gradient[i];
    fluid.correction[i] = w[i] * correction;
  }
}

}  // namespace moreau
