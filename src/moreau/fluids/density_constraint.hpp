#pragma once
// The incompressibility constraint of Position Based Fluids (Macklin & Mueller 2013), one per
// fluid particle: what every solver reads from the fluid.
//
// Constraint (volume form; equals rho_i / rho0 - 1 for a single fluid, and lets fluids of
// different rest density share one lattice volume V, as in Solenthaler & Pajarola 2008):
//   C_i = V sum_j W(x_i - x_j) + sum_b V_b W(x_i - x_b) - 1       (j: fluid, incl. i; b: wall samples)
// Gradients (grad W w.r.t. its argument):
//   grad_{x_i} C_i = V sum_{j != i} grad W_ij + sum_b V_b grad W_ib,    grad_{x_j} C_i = -V grad W_ij
// Units: C is dimensionless; the gradients are in 1/m.
// The XPBD solver's Jacobi projection of these constraints (the PBF multiplier, its relaxation and
// the tensile term) is solvers/xpbd/project_fluid_density.hpp.
#include "moreau/fluids/fluid_state.hpp"
#include "moreau/fluids/pair_chunks.hpp"

namespace moreau {

/// Constraint C_i evaluated at the fluid's positions, with what a solver needs of its gradient:
/// grad_{x_i} C_i, the part of it from walls and solid samples, and the inverse-mass weighted
/// squared gradients of the other particles it moves (the off-i diagonal of J W J^T): the fluid
/// neighbours' V^2 sum_j w_j |grad W_ij|^2 (kept without the factor V^2, which the solver applies
/// where it forms its denominator) and the solid samples' sum_s w_s V_s^2 |grad W_is|^2.
struct DensityEvaluation {
  Real C;
  Vec3 gradient;            // grad_{x_i} C_i, 1/m
  Vec3 boundary_gradient;   // sum_b V_b grad W_ib over wall and solid samples, 1/m
  Real fluid_kernel_weight; // sum_j w_j |grad W_ij|^2, 1/(kg m^8)
  Real solid_weight;        // 1/(kg m^2)
};

/// Where evaluate_density_constraint leaves each fluid pair's kernel value W_ij and gradient
/// grad W_ij = g_ij (x_i - x_j), so that a second pass over the same positions reads them instead
/// of evaluating the kernel again. Row i's pairs start at offset[i], in whole chunks of kPairChunk
/// lanes (pad lanes hold zeros).
struct DensityPairCache {
  const Index* offset;
  Real* w;
  Real* gx;
  Real* gy;
  Real* gz;
};

/// C_i of fluid particle i over its current neighbour lists (call between list rebuilds);
/// `solid_inv_mass` holds the solid samples' inverse masses of this substep (split_solid_masses;
/// unread without solids).
/// Chunked so that the compiler vectorises the pair sums (pair_chunks.hpp); inlined into the
/// solver's loop so that each of its instruction-set clones vectorises it for its own width.
[[gnu::always_inline]] inline DensityEvaluation evaluate_density_constraint(const FluidModel& fm,
                                                                              const FluidState& fluid,
                                                                              const Real* solid_inv_mass, Index i,
                                                                              const DensityPairCache* cache = nullptr) {
  const CubicSplineKernel kernel = fm.kernel;
  const Real V = fm.particle_volume, pad = 2 * kernel.h;
  const Vec3* x = fluid.position.data();
  const Vec3* xb = fluid.boundary_position.data();
  const Real* wall_volume = fm.boundary.volume.data();
  const Vec3* xs = fluid.solid_position.data();
  const Real* solid_volume = fm.solid.volume.data();
  const Real* w = fluid.inv_mass.data();
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
    if (cache) {
      const Index at = cache->offset[i] + begin;
      #pragma omp simd
      for (int k = 0; k < kPairChunk; ++k) {
        cache->w[at + k] = chunk.w[k];
        cache->gx[at + k] = chunk.g[k] * chunk.rx[k];
        cache->gy[at + k] = chunk.g[k] * chunk.ry[k];
        cache->gz[at + k] = chunk.g[k] * chunk.rz[k];
      }
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
  return {C, grad_i, wall_gradient, neighbor_term, solid_term};
}

/// Visits the gradient of C_i with respect to every other particle it moves, as
/// f(kind, index, gradient): fluid neighbours j (grad_{x_j} C_i = -V grad W_ij) and solid samples s
/// (grad_{x_s} C_i = -V_s grad W_is); wall samples do not move. With grad_{x_i} C_i these are the
/// constraint's rows for a solver that assembles them.
enum class DensityNeighbor { fluid, solid_sample };
template <class Visit>
void for_each_density_gradient(const FluidModel& fm, const FluidState& fluid, Index i, Visit&& f) {
  const CubicSplineKernel& kernel = fm.kernel;
  const Vec3& xi = fluid.position[i];
  auto visit = [&](const FixedStrideLists& lists, const Vec3* x, DensityNeighbor kind, auto&& volume) {
    const Index* row = lists.row(i);
    for (Index k = 0; k < lists.count[i]; ++k) {
      const Index j = row[k];
      const Vec3 r = xi - x[j];
      const Real d = r.norm();
      if (d >= kernel.h) continue;
      f(kind, j, Vec3(-volume(j) * kernel.gradient_factor(d) * r));
    }
  };
  visit(fluid.fluid_neighbors, fluid.position.data(), DensityNeighbor::fluid, [&](Index) { return fm.particle_volume; });
  visit(fluid.solid_neighbors, fluid.solid_position.data(), DensityNeighbor::solid_sample,
        [&](Index s) { return fm.solid.volume[s]; });
}

/// The rest-lattice denominator D_rest (1/(kg m^2)) of a particle of mass m (kg); used by the
/// scene builder to scale the relaxation.
Real fluid_rest_denominator(const CubicSplineKernel& kernel, Real spacing, Real mass);

}  // namespace moreau
