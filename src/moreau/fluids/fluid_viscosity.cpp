#include "moreau/fluids/fluid_viscosity.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "moreau/collision/point_query.hpp"
#include "moreau/fluids/interface_viscosity.hpp"
#include "moreau/fluids/neighbor_loop.hpp"
#include "moreau/fluids/pair_chunks.hpp"
#include "moreau/fluids/solid_gather.hpp"
#include "moreau/fluids/wall_extrapolation.hpp"
#include "moreau/math/target_clones.hpp"
#include "moreau/model/model.hpp"
#include "moreau/model/state.hpp"

namespace moreau {
namespace {

constexpr Real kCorrectionFloor = 0.2;  // smallest eigenvalue of M_k kept (1 in a full neighbourhood)
constexpr Index kDotBlock = 512;        // particles per partial dot product
constexpr Real kLaplacianFactor = 10;   // 2 (d + 2), d = 3: Monaghan's compact Laplacian

/// M^-1 with M's eigenvalues floored at kCorrectionFloor. For a symmetric positive semidefinite M,
/// lambda_min = det / (lambda_mid lambda_max) >= 4 det / trace^2 (as lambda_mid + lambda_max <= trace),
/// so where that bound clears the floor the plain inverse is the floored one and the
/// eigen-decomposition is skipped (every particle with a full neighbourhood: M = I gives 4/9). A
/// particle without neighbours (M = 0) gets 1/floor I, and a zero gradient.
Mat3 floored_inverse(const Mat3& moment) {
  const Real trace = moment.trace(), det = moment.determinant();
  if (trace > 0 && 4 * det >= kCorrectionFloor * trace * trace) return moment.inverse();
  Eigen::SelfAdjointEigenSolver<Mat3> eigen;
  eigen.computeDirect(moment);
  const Vec3 inverse = eigen.eigenvalues().cwiseMax(kCorrectionFloor).cwiseInverse();
  return eigen.eigenvectors() * inverse.asDiagonal() * eigen.eigenvectors().transpose();
}

/// Calls visit(s, friction, r, d2) for every solid sample s with fluid friction (the surface of a
/// rigid body, a cloth, a soft body or a continuum) within the kernel support of fluid particle k,
/// r = x_k - x_s, d2 = |r|^2; with `kExtrapolate`, visit(s, friction, r, d2, beta, u_wall) for the
/// wall terms.
///
/// A cloth, soft-body or continuum sample moves with its particles, u_wall = sum_i b_i v_i
/// (place_rough_samples), and is not extrapolated (beta = 1): a sheet's samples lie on the sheet
/// itself, so the fluid sticks to it there; a soft body's lie r inside its surface and a
/// continuum's at its particles' centres, half its spacing inside, where the fluid's velocity then
/// matches the solid's (a slip length of about that depth at a shear).
///
/// As at the collider walls (wall_extrapolation.hpp), the sample takes the velocity that
/// extrapolates the particle's linearly through the surface (Morris, Fox & Zhu 1997):
///   u_k - u_s = beta (u_k - u_wall),  beta = 1 + r_p / max(d_k, r_p),
/// with r_p the depth of the samples behind the surface and d_k the particle's distance from the
/// body's shape (point_query.hpp; computed again whenever the next sample in the particle's list
/// belongs to another body; a mesh body with no triangle within one grid cell of the particle
/// gives d_k = infinity and beta = 1). u_wall is the body's velocity where the segment from x_k to
/// x_s crosses the surface, x_k - r / beta (the segment is split d_k : r_p there), so that liquid
/// turning with the body has u_s = the body's velocity at x_s and no shear. (The body's velocity
/// at the sample's own surface point instead puts a shear on liquid next to a turning body: beta
/// times the body's turning across r.)
template <bool kExtrapolate, class Visit>
void for_each_rough_solid_sample(const Model& model, const FluidState& fluid, const FluidScratch& s, Index k,
                                 Visit&& visit) {
  const FluidModel& fm = model.fluid;
  if (!fm.solid.any_friction) return;
  const Real h2 = fm.kernel.h2, depth = fm.particle_radius;
  const Vec3 xk = fluid.position[k];
  Index cached_body = -1;
  Real beta = 1;
  const Index* row = fluid.solid_neighbors.row(k);
  for (Index n = 0; n < fluid.solid_neighbors.count[k]; ++n) {
    const Index sample = row[n];
    const Real friction = fm.solid.friction[sample];
    if (friction == 0) continue;
    const Vec3 r = xk - fluid.solid_position[sample];
    const Real d2 = r.squaredNorm();
    if (d2 >= h2) continue;
    if constexpr (kExtrapolate) {
      const Index b = fm.solid.body[sample];
      if (b < 0) {
        visit(sample, friction, r, d2, Real(1), s.solid_wall_velocity[sample]);
        continue;
      }
      const FluidScratch::RigidSurfaceMotion& body = s.rough_body[b];
      if (b != cached_body) {
        cached_body = b;
        const Real distance = nearest_surface_point(model.rigid.body_shape[b], body.pose.to_local(xk)).distance;
        beta = 1 + depth / std::max(distance, depth);
      }
      const Vec3 crossing = xk - r / beta;
      visit(sample, friction, r, d2, beta, Vec3(body.velocity + body.angular_velocity.cross(crossing - body.pose.position)));
    } else {
      visit(sample, friction, r, d2);
    }
  }
}

/// The wall sums of particle k: its walls' part of M_k, q_k and P_k (Morris et al. 1997: a sample's
/// velocity extrapolates v_k through the wall), over the collider walls and the rigid surfaces
/// with fluid friction.
void wall_sums(const Model& model, const FluidState& fluid, const FluidScratch& s, Index k, Mat3& moment,
               Vec3& wall_sum, Mat3& wall_velocity_sum) {
  const FluidModel& fm = model.fluid;
  wall_sum.setZero();
  wall_velocity_sum.setZero();
  for_each_extrapolated_wall_sample(
      model, fluid, k, [](const Collider& c) { return c.fluid_friction != 0; },
      [&](Index b, const Collider& c, const Vec3& r, Real d2, Real beta) {
        const Real weight = c.fluid_friction * fm.boundary.volume[b] * fm.kernel.gradient_factor(std::sqrt(d2));
        moment -= weight * r * r.transpose();
        wall_sum += (weight * beta) * r;
        wall_velocity_sum += (weight * beta) * c.velocity * r.transpose();
      });
  for_each_rough_solid_sample<true>(
      model, fluid, s, k, [&](Index sample, Real friction, const Vec3& r, Real d2, Real beta, const Vec3& wall_velocity) {
        const Real weight = friction * fm.solid.volume[sample] * fm.kernel.gradient_factor(std::sqrt(d2));
        moment -= weight * r * r.transpose();
        wall_sum += (weight * beta) * r;
        wall_velocity_sum += (weight * beta) * wall_velocity * r.transpose();
      });
}

/// Over the fluid neighbours j of k, in chunks the compiler vectorises (pair_chunks.hpp):
///   gradient = sum_j g_kj (u_j - u_k) r_kj^T,   moment = -sum_j g_kj r_kj r_kj^T  (if `with_moment`).
MOREAU_TARGET_CLONES void fluid_gradient_sums(const FluidState& fluid, const Vec3* u, Index k,
                                              const CubicSplineKernel& kernel, bool with_moment, Mat3& gradient,
                                              Mat3& moment) {
  const Vec3* x = fluid.position.data();
  const Vec3 xk = x[k], uk = u[k];
  const Real pad = 2 * kernel.h;
  PairChunk chunk;
  alignas(64) Real dux[kPairChunk], duy[kPairChunk], duz[kPairChunk];
  alignas(64) Real gxx[kPairChunk] = {}, gxy[kPairChunk] = {}, gxz[kPairChunk] = {}, gyx[kPairChunk] = {},
                   gyy[kPairChunk] = {}, gyz[kPairChunk] = {}, gzx[kPairChunk] = {}, gzy[kPairChunk] = {},
                   gzz[kPairChunk] = {};
  alignas(64) Real mxx[kPairChunk] = {}, mxy[kPairChunk] = {}, mxz[kPairChunk] = {}, myy[kPairChunk] = {},
                   myz[kPairChunk] = {}, mzz[kPairChunk] = {};
  const Index* row = fluid.fluid_neighbors.row(k);
  const Index count = fluid.fluid_neighbors.count[k];
  for (Index begin = 0; begin < count; begin += kPairChunk) {
    chunk.load(xk, x, row, begin, count, pad);
    for (int l = 0; l < kPairChunk; ++l) {
      const Vec3 du = begin + l < count ? Vec3(u[row[begin + l]] - uk) : Vec3::Zero();
      dux[l] = du.x(), duy[l] = du.y(), duz[l] = du.z();
    }
    chunk.evaluate(kernel);
#pragma omp simd
    for (int l = 0; l < kPairChunk; ++l) {
      // Pad lanes and list entries beyond h have g = 0.
      const Real gx = chunk.g[l] * chunk.rx[l], gy = chunk.g[l] * chunk.ry[l], gz = chunk.g[l] * chunk.rz[l];
      gxx[l] += dux[l] * gx, gxy[l] += dux[l] * gy, gxz[l] += dux[l] * gz;
      gyx[l] += duy[l] * gx, gyy[l] += duy[l] * gy, gyz[l] += duy[l] * gz;
      gzx[l] += duz[l] * gx, gzy[l] += duz[l] * gy, gzz[l] += duz[l] * gz;
      mxx[l] -= chunk.rx[l] * gx, mxy[l] -= chunk.rx[l] * gy, mxz[l] -= chunk.rx[l] * gz;
      myy[l] -= chunk.ry[l] * gy, myz[l] -= chunk.ry[l] * gz, mzz[l] -= chunk.rz[l] * gz;
    }
  }
  gradient << sum_lanes(gxx), sum_lanes(gxy), sum_lanes(gxz), sum_lanes(gyx), sum_lanes(gyy), sum_lanes(gyz),
      sum_lanes(gzx), sum_lanes(gzy), sum_lanes(gzz);
  moment.setZero();
  if (with_moment) {
    const Real xy = sum_lanes(mxy), xz = sum_lanes(mxz), yz = sum_lanes(myz);
    moment << sum_lanes(mxx), xy, xz, xy, sum_lanes(myy), yz, xz, yz, sum_lanes(mzz);
  }
}

/// The gradient pass: G_k(u) and S_k = 2 mu_k sym(G_k) L_k for every particle. `setup` (the solve's
/// first pass, u = v*) also forms L_k, q_k, P_k and, next to walls, the fluid-only correction, and
/// includes the walls' velocities; later passes (the homogeneous operator K) reuse them without the
/// walls' velocities.
void gradient_pass(const Model& model, const FluidState& fluid, FluidScratch& s, const Vec3* u, bool setup) {
  const FluidModel& fm = model.fluid;
  const CubicSplineKernel& kernel = fm.kernel;
  const Real V = fm.particle_volume;
#pragma omp for schedule(static)
  for (Index k = 0; k < fluid.count; ++k) {
    const Vec3 uk = u[k];
    Mat3 gradient, moment;
    fluid_gradient_sums(fluid, u, k, kernel, setup, gradient, moment);
    gradient *= V;
    moment *= V;
    if (setup) {
      s.stress_viscosity[k] = stress_viscosity(fm, fluid, k);
      const Mat3 fluid_moment = moment;
      wall_sums(model, fluid, s, k, moment, s.wall_sum[k], s.wall_velocity_sum[k]);
      s.gradient_correction[k] = floored_inverse(moment);
      // The wall traction's gradient of the stress is taken over the fluid neighbours alone.
      if (!s.wall_sum[k].isZero()) s.fluid_gradient_correction[k] = floored_inverse(fluid_moment);
      gradient += s.wall_velocity_sum[k];
    }
    gradient -= uk * s.wall_sum[k].transpose();
    const Mat3& correction = s.gradient_correction[k];
    const Mat3 G = gradient * correction;
    s.velocity_gradient[k] = G;
    s.corrected_stress[k] = (s.stress_viscosity[k] * (G + G.transpose())) * correction;
  }
}

/// dS/dx_c of particle k's corrected stress, c = x, y, z, by the corrected gradient over its fluid
/// neighbours alone: what extrapolates the stress to the wall samples.
std::array<Mat3, 3> stress_slope(const Model& model, const FluidState& fluid, const FluidScratch& s, Index k) {
  const Real V = model.fluid.particle_volume;
  const Mat3& Sk = s.corrected_stress[k];
  const Mat3& correction = s.fluid_gradient_correction[k];
  std::array<Mat3, 3> slope = {Mat3::Zero(), Mat3::Zero(), Mat3::Zero()};
  for_each_fluid_neighbor(fluid, model.fluid.kernel, k, [&](Index j, const Vec3& r, Real g) {
    const Vec3 c = (V * g) * (correction * r);
    const Mat3 difference = s.corrected_stress[j] - Sk;
    for (int a = 0; a < 3; ++a) slope[a] += c[a] * difference;
  });
  return slope;
}

/// One wall sample's traction on particle k over the particle's volume V, f V_b g_kb (S_b + S_k) r_kb
/// (N/m^3), with the stress at the sample extrapolated from the particle's, S_b = S_k + grad S_k
/// (x_b - x_k). (Taking S_b = S_k, as the adjoint of the wall terms of G would, gives a wall shear
/// stress half the exact one in Poiseuille flow.)
Vec3 wall_sample_traction(const Model& model, const Mat3& Sk, const std::array<Mat3, 3>& slope, const Vec3& r, Real d2,
                          Real friction, Real sample_volume) {
  const Mat3 Sb = Sk - r.x() * slope[0] - r.y() * slope[1] - r.z() * slope[2];
  return (friction * sample_volume * model.fluid.kernel.gradient_factor(std::sqrt(d2))) * ((Sb + Sk) * r);
}

/// The wall samples' share of f_k: the traction of every collider wall sample and rigid surface
/// sample with fluid friction.
Vec3 wall_traction(const Model& model, const FluidState& fluid, const FluidScratch& s, Index k) {
  const FluidModel& fm = model.fluid;
  const FluidBoundarySamples& samples = fm.boundary;
  const Vec3 xk = fluid.position[k];
  const Mat3& Sk = s.corrected_stress[k];
  const std::array<Mat3, 3> slope = stress_slope(model, fluid, s, k);
  Vec3 traction = Vec3::Zero();
  const Index* walls = fluid.boundary_neighbors.row(k);
  for (Index n = 0; n < fluid.boundary_neighbors.count[k]; ++n) {
    const Index b = walls[n];
    const Real friction = model.colliders[samples.collider[b]].fluid_friction;
    if (friction == 0) continue;
    const Vec3 r = xk - fluid.boundary_position[b];
    const Real d2 = r.squaredNorm();
    if (d2 >= fm.kernel.h2) continue;
    traction += wall_sample_traction(model, Sk, slope, r, d2, friction, samples.volume[b]);
  }
  for_each_rough_solid_sample<false>(model, fluid, s, k, [&](Index sample, Real friction, const Vec3& r, Real d2) {
    traction += wall_sample_traction(model, Sk, slope, r, d2, friction, fm.solid.volume[sample]);
  });
  return fm.particle_volume * traction;
}

/// The force pass for particle k: the stress divergence
///   f_k = V^2 sum_j g_kj (S_j + S_k) r_kj + the walls' traction
/// plus the stabilising term m_k L(e)_k (below), from the last gradient pass. With `diagonal`,
/// the stabilising term's block that multiplies u_k directly (negative semidefinite; the part
/// through G_k is left out of the preconditioner).
///
/// Stabilisation: Monaghan's compact Laplacian of the pairs' departure from the corrected gradients,
///   e_kj = u_k - u_j - (G_k + G_j) r_kj / 2     (zero for any quadratic u: trapezoidal rule)
///   L_k  = 10 sum_j V mu_kj nu_kj g_kj (r_kj . e_kj) r_kj / (r^2 + 0.01 h^2),
/// damps the particle-scale (odd-even) velocity modes the wide stencil of the stress divergence
/// cannot see, without changing its value for smooth flow. e_kj = -e_jk and the pair term lies
/// along r_kj, so it conserves linear and angular momentum.
MOREAU_TARGET_CLONES Vec3 viscous_force(const Model& model, const FluidState& fluid, const FluidScratch& s,
                                         const Vec3* u, Index k, Mat3* diagonal) {
  const FluidModel& fm = model.fluid;
  const CubicSplineKernel kernel = fm.kernel;
  const Real V = fm.particle_volume, eta2 = 0.01 * kernel.h2, pad = 2 * kernel.h;
  const Vec3* x = fluid.position.data();
  const Vec3 xk = x[k], uk = u[k];
  const Mat3& Sk = s.corrected_stress[k];
  const Mat3& Gk = s.velocity_gradient[k];
  const Real w_k = fluid.inv_mass[k];
  if (w_k == 0) {  // a solid or held particle (fluid_heat.hpp, fluid_emitter.hpp): its row is m_k u_k, so its change stays 0
    if (diagonal) diagonal->setZero();
    return Vec3::Zero();
  }
  PairChunk chunk;
  // Per lane: u_j, nu_kj, S_j and G_j (row-major).
  alignas(64) Real ux[kPairChunk], uy[kPairChunk], uz[kPairChunk], nu[kPairChunk], S[9][kPairChunk], G[9][kPairChunk];
  alignas(64) Real fx[kPairChunk] = {}, fy[kPairChunk] = {}, fz[kPairChunk] = {};
  alignas(64) Real kx[kPairChunk] = {}, ky[kPairChunk] = {}, kz[kPairChunk] = {};
  alignas(64) Real ex[kPairChunk] = {}, ey[kPairChunk] = {}, ez[kPairChunk] = {};
  alignas(64) Real bxx[kPairChunk] = {}, bxy[kPairChunk] = {}, bxz[kPairChunk] = {}, byy[kPairChunk] = {},
                   byz[kPairChunk] = {}, bzz[kPairChunk] = {};
  const Index* row = fluid.fluid_neighbors.row(k);
  const Index count = fluid.fluid_neighbors.count[k];
  for (Index begin = 0; begin < count; begin += kPairChunk) {
    chunk.load(xk, x, row, begin, count, pad, fluid.inv_mass.data());
    for (int l = 0; l < kPairChunk; ++l) {
      const Index j = begin + l < count ? row[begin + l] : k;  // pad lanes have g = 0
      ux[l] = u[j].x(), uy[l] = u[j].y(), uz[l] = u[j].z();
      nu[l] = pair_viscosity(fm, fluid, k, j);
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) {
          S[3 * a + b][l] = s.corrected_stress[j](a, b);
          G[3 * a + b][l] = Gk(a, b) + s.velocity_gradient[j](a, b);
        }
    }
    chunk.evaluate(kernel);
#pragma omp simd
    for (int l = 0; l < kPairChunk; ++l) {
      const Real rx = chunk.rx[l], ry = chunk.ry[l], rz = chunk.rz[l], g = chunk.g[l];
      fx[l] += g * (S[0][l] * rx + S[1][l] * ry + S[2][l] * rz);
      fy[l] += g * (S[3][l] * rx + S[4][l] * ry + S[5][l] * rz);
      fz[l] += g * (S[6][l] * rx + S[7][l] * ry + S[8][l] * rz);
      kx[l] += g * rx, ky[l] += g * ry, kz[l] += g * rz;
      // Pad lanes have inverse mass 0 (mu = 2) and g = 0: every term vanishes.
      const Real mu = 2 * w_k / (w_k + chunk.a[l]);
      const Real c = mu * nu[l] * g / (rx * rx + ry * ry + rz * rz + eta2);
      const Real dx = uk.x() - ux[l] - 0.5 * (G[0][l] * rx + G[1][l] * ry + G[2][l] * rz);
      const Real dy = uk.y() - uy[l] - 0.5 * (G[3][l] * rx + G[4][l] * ry + G[5][l] * rz);
      const Real dz = uk.z() - uz[l] - 0.5 * (G[6][l] * rx + G[7][l] * ry + G[8][l] * rz);
      const Real e = c * (rx * dx + ry * dy + rz * dz);
      ex[l] += e * rx, ey[l] += e * ry, ez[l] += e * rz;
      bxx[l] += c * rx * rx, bxy[l] += c * rx * ry, bxz[l] += c * rx * rz;
      byy[l] += c * ry * ry, byz[l] += c * ry * rz, bzz[l] += c * rz * rz;
    }
  }
  const Real scale = fluid.mass[k] * kLaplacianFactor * V;
  if (diagonal) {
    const Real xy = sum_lanes(bxy), xz = sum_lanes(bxz), yz = sum_lanes(byz);
    *diagonal << sum_lanes(bxx), xy, xz, xy, sum_lanes(byy), yz, xz, yz, sum_lanes(bzz);
    *diagonal *= scale;
  }
  const Vec3 stress(sum_lanes(fx), sum_lanes(fy), sum_lanes(fz));
  const Vec3 kernel_sum(sum_lanes(kx), sum_lanes(ky), sum_lanes(kz));
  const Vec3 stabilising(sum_lanes(ex), sum_lanes(ey), sum_lanes(ez));
  Vec3 force = (V * V) * (stress + Sk * kernel_sum) + scale * stabilising;
  if (!s.wall_sum[k].isZero()) force += wall_traction(model, fluid, s, k);
  return force;
}

/// The diagonal block m_k I + dt sum_i V mu_i (|c_ik|^2 I + c_ik c_ik^T) of M + dt K, inverted.
Mat3 inverse_diagonal_block(const Model& model, const FluidState& fluid, const FluidScratch& s, Index k, Real dt,
                            const Mat3& stabilising_diagonal) {
  const FluidModel& fm = model.fluid;
  const CubicSplineKernel& kernel = fm.kernel;
  const Real V = fm.particle_volume;
  Mat3 block = Mat3::Zero();
  Vec3 own = s.wall_sum[k];  // c_kk = -L_k (sum_j V g_kj r_kj + q_k)
  for_each_fluid_neighbor(fluid, kernel, k, [&](Index i, const Vec3& r, Real g) {
    own += (V * g) * r;
    const Vec3 c = -(V * g) * (s.gradient_correction[i] * r);  // c_ik = V g_ik L_i r_ik, r_ik = -r
    block += s.stress_viscosity[i] * (c.squaredNorm() * Mat3::Identity() + c * c.transpose());
  });
  const Vec3 c = -(s.gradient_correction[k] * own);
  block += s.stress_viscosity[k] * (c.squaredNorm() * Mat3::Identity() + c * c.transpose());
  return (fluid.mass[k] * Mat3::Identity() + (dt * V) * block - dt * stabilising_diagonal).inverse();
}

/// The sum of the block partial sums [begin, end), in block order (every thread gets the same value).
Real sum_blocks(const std::vector<Real>& partial, Index begin, Index end) {
  Real s = 0;
  for (Index k = begin; k < end; ++k) s += partial[k];
  return s;
}

/// A u = M u - dt f0(u) for particle k, after gradient_pass(u) without wall velocities.
Vec3 apply_system(const Model& model, const FluidState& fluid, const FluidScratch& s, const Vec3* u, Index k, Real dt) {
  return fluid.mass[k] * u[k] - dt * viscous_force(model, fluid, s, u, k, nullptr);
}

/// Right-preconditioned BiCGSTAB (van der Vorst 1992) on (M + dt K) dv = dt f(v*), from dv = 0.
/// K is symmetric but for the wall traction's extrapolated stress, so CG does not apply.
void implicit_solve(const Model& model, FluidState& fluid, FluidScratch& s, Real dt) {
  const FluidModel& fm = model.fluid;
  const Index n = fluid.count, blocks = (n + kDotBlock - 1) / kDotBlock;
  std::vector<Vec3>&x = s.viscous_change, &r = s.solve_residual, &shadow = s.solve_shadow, &p = s.solve_direction,
  &v = s.solve_direction_image, &y = s.solve_preconditioned, &w = s.solve_intermediate,
  &t = s.solve_intermediate_image;
#pragma omp single
  {
    if (s.block_sum_a.size() < static_cast<std::size_t>(2 * blocks)) {
      s.block_sum_a.resize(2 * blocks);
      s.block_sum_b.resize(2 * blocks);
    }
  }
  auto range_end = [&](Index block) { return std::min(n, (block + 1) * kDotBlock); };
  // Right-hand side b = dt f(v*) and the diagonal blocks.
  gradient_pass(model, fluid, s, fluid.velocity.data(), true);
#pragma omp for schedule(static)
  for (Index block = 0; block < blocks; ++block) {
    Real bb = 0;
    for (Index k = block * kDotBlock; k < range_end(block); ++k) {
      Mat3 stabilising_diagonal;
      const Vec3 force = viscous_force(model, fluid, s, fluid.velocity.data(), k, &stabilising_diagonal);
      s.inverse_diagonal[k] = inverse_diagonal_block(model, fluid, s, k, dt, stabilising_diagonal);
      x[k].setZero();
      r[k] = dt * force;
      shadow[k] = r[k];
      p[k].setZero();
      v[k].setZero();
      bb += r[k].squaredNorm();
    }
    s.block_sum_a[block] = bb;
  }
  const Real bb = sum_blocks(s.block_sum_a, 0, blocks);
  Real rho = 1, alpha = 1, omega = 1, rr = bb;
  int iterations = 0;
  Real residual = 0;
  while (bb > 0) {
    residual = std::sqrt(rr / bb);
    if (residual <= fm.viscosity_tolerance || iterations == fm.viscosity_max_iterations) break;
    ++iterations;
    // rho = shadow . r (summed in the previous pass: block_sum_b[blocks..] holds it after the first)
#pragma omp for schedule(static)
    for (Index block = 0; block < blocks; ++block) {
      Real sr = 0;
      for (Index k = block * kDotBlock; k < range_end(block); ++k) sr += shadow[k].dot(r[k]);
      s.block_sum_b[block] = sr;
    }
    const Real rho_next = sum_blocks(s.block_sum_b, 0, blocks);
    const Real beta = (rho_next / rho) * (alpha / omega);
    rho = rho_next;
#pragma omp for schedule(static)
    for (Index k = 0; k < n; ++k) {
      p[k] = r[k] + beta * (p[k] - omega * v[k]);
      y[k] = s.inverse_diagonal[k] * p[k];
    }
    gradient_pass(model, fluid, s, y.data(), false);
#pragma omp for schedule(static)
    for (Index block = 0; block < blocks; ++block) {
      Real sv = 0;
      for (Index k = block * kDotBlock; k < range_end(block); ++k) {
        v[k] = apply_system(model, fluid, s, y.data(), k, dt);
        sv += shadow[k].dot(v[k]);
      }
      s.block_sum_a[block] = sv;
    }
    alpha = rho / sum_blocks(s.block_sum_a, 0, blocks);
#pragma omp for schedule(static)
    for (Index k = 0; k < n; ++k) {
      x[k] += alpha * y[k];
      w[k] = r[k] - alpha * v[k];
      y[k] = s.inverse_diagonal[k] * w[k];
    }
    gradient_pass(model, fluid, s, y.data(), false);
#pragma omp for schedule(static)
    for (Index block = 0; block < blocks; ++block) {
      Real tw = 0, tt = 0;
      for (Index k = block * kDotBlock; k < range_end(block); ++k) {
        t[k] = apply_system(model, fluid, s, y.data(), k, dt);
        tw += t[k].dot(w[k]);
        tt += t[k].squaredNorm();
      }
      s.block_sum_b[block] = tw;
      s.block_sum_b[blocks + block] = tt;
    }
    const Real tt = sum_blocks(s.block_sum_b, blocks, 2 * blocks);
    omega = tt > 0 ? sum_blocks(s.block_sum_b, 0, blocks) / tt : 0;
#pragma omp for schedule(static)
    for (Index block = 0; block < blocks; ++block) {
      Real rr_block = 0;
      for (Index k = block * kDotBlock; k < range_end(block); ++k) {
        x[k] += omega * y[k];
        r[k] = w[k] - omega * t[k];
        rr_block += r[k].squaredNorm();
      }
      s.block_sum_a[block] = rr_block;
    }
    rr = sum_blocks(s.block_sum_a, 0, blocks);
    if (omega == 0) break;  // breakdown: keep the iterate
  }
  if (bb > 0) residual = std::sqrt(rr / bb);
#pragma omp single
  {
    ViscositySolveStats& stats = fluid.viscosity_stats;
    ++stats.solves;
    stats.iterations += iterations;
    stats.most_iterations = std::max(stats.most_iterations, iterations);
    if (residual > fm.viscosity_tolerance) ++stats.unconverged;
    stats.worst_residual = std::max(stats.worst_residual, residual);
  }
}

/// Every rough sample placed where its solid is now (the last placement, before the density solve
/// under XPBD and before the step's motion under nmd, lags the solid by what the contacts, joints
/// or the step moved it since): a rigid body's at x_s = x_b + q_b s, with each body's pose and
/// velocities kept for the extrapolation through its surface (for_each_rough_solid_sample); a
/// cloth, soft-body or continuum sample at x_s = sum_i b_i x_i with the velocity u_s = sum_i b_i v_i.
void place_rough_samples(const Model& model, State& state, FluidScratch& s) {
  const FluidSolidSamples& samples = model.fluid.solid;
  const RigidBodyState& rigid = state.rigid;
#pragma omp single
  for (Index b : samples.sampled_body)
    s.rough_body[b] = {Pose{rigid.position[b], rigid.orientation[b]}, rigid.velocity[b], rigid.angular_velocity[b]};
#pragma omp for schedule(static)
  for (Index sample = 0; sample < samples.size(); ++sample) {
    if (samples.friction[sample] == 0) continue;
    const Index b = samples.body[sample];
    if (b >= 0) {
      state.fluid.solid_position[sample] = rigid.position[b] + rigid.orientation[b] * samples.body_point[sample];
      continue;
    }
    Vec3 x = Vec3::Zero(), v = Vec3::Zero();
    for (int slot = 0; slot < 4; ++slot) {
      const Index p = samples.particle[sample][slot];
      const Real weight = samples.weight[sample][slot];
      x += weight * state.position[p];
      v += weight * state.velocity[p];
    }
    state.fluid.solid_position[sample] = x;
    s.solid_wall_velocity[sample] = v;
  }
}

/// The viscous reaction on the solids with fluid friction, after the solve has set the velocities
/// v = v* + dv. Backward Euler made the fluid's velocity change the impulse h f(v), so the walls'
/// share of it is h times their traction at v: each sample s takes the opposite,
///   F_s = -sum_k t_ks(v),   t_ks = V f V_s g_ks (S_s + S_k) r_ks     (wall_sample_traction),
/// summed over the sample's fluid particles (the reverse lists, in their fixed order). Each
/// dynamic rigid body takes the impulse of its samples' forces at their points,
///   v_b += h/m sum_s F_s,   w_b += h I_b^-1 sum_s (x_s - x_b) x F_s,
/// and each cloth, soft-body or continuum particle its share by the samples' barycentric weights
/// (under xpbi the continuum's end of substep then moves the particle by x = x^n + h v with it),
///   v_i += h w_i sum_s b_si F_s.
/// Momentum is then kept to the solve's tolerance: the fluid's other viscous terms are pairwise
/// equal and opposite. The solid's change is explicit (it follows the fluid's implicit one), which
/// is stable while the solid outweighs the fluid its surface drags within a viscosity step: per unit of
/// area, about rho sqrt(nu h) of fluid against the mass of the solid's surface layer (a
/// particle's mass over its share of the surface).
void apply_rough_solid_reactions(const Model& model, State& state, FluidScratch& s, Real h) {
  const FluidModel& fm = model.fluid;
  const FluidSolidSamples& samples = fm.solid;
  FluidState& fluid = state.fluid;
  RigidBodyState& rigid = state.rigid;
  gradient_pass(model, fluid, s, fluid.velocity.data(), true);
#pragma omp for schedule(static)
  for (Index k = 0; k < fluid.count; ++k) {
    bool rough = false;
    for_each_rough_solid_sample<false>(model, fluid, s, k, [&](Index, Real, const Vec3&, Real) { rough = true; });
    if (rough) s.stress_slope[k] = stress_slope(model, fluid, s, k);
  }
#pragma omp for schedule(static)
  for (Index sample = 0; sample < samples.size(); ++sample) {
    Vec3 force = Vec3::Zero();
    const Real friction = samples.friction[sample];
    if (friction > 0) {
      const Index* row = fluid.solid_fluids.row(sample);
      for (Index n = 0; n < fluid.solid_fluids.count[sample]; ++n) {
        const Index k = row[n];
        if (fluid.inv_mass[k] == 0) continue;  // a solid or held particle: the solve leaves its velocity
        const Vec3 r = fluid.position[k] - fluid.solid_position[sample];
        const Real d2 = r.squaredNorm();
        if (d2 >= fm.kernel.h2) continue;
        force -= wall_sample_traction(model, s.corrected_stress[k], s.stress_slope[k], r, d2, friction,
                                      samples.volume[sample]);
      }
    }
    s.solid_viscous_force[sample] = fm.particle_volume * force;
  }
#pragma omp single
  for (std::size_t j = 0; j < samples.sampled_body.size(); ++j) {
    const Index b = samples.sampled_body[j];
    const Real inv_mass = model.rigid.body_inv_mass[b];
    if (inv_mass == 0) continue;
    Vec3 force = Vec3::Zero(), torque = Vec3::Zero();
    for (Index sample = samples.body_begin[j]; sample < samples.body_begin[j + 1]; ++sample) {
      force += s.solid_viscous_force[sample];
      torque += (fluid.solid_position[sample] - rigid.position[b]).cross(s.solid_viscous_force[sample]);
    }
    const Mat3 R = rigid.orientation[b].toRotationMatrix();
    rigid.velocity[b] += (h * inv_mass) * force;
    rigid.angular_velocity[b] += h * (R * model.rigid.body_inv_inertia[b].asDiagonal() * R.transpose() * torque);
  }
  if (samples.any_particle_friction)
    gather_to_solid_particles(model, s.solid_viscous_force.data(), [&](Index p, Real w, const Vec3& force) {
      state.velocity[p] += (h * w) * force;
    });
}

}  // namespace

bool fluid_has_viscosity(const Model& model) {
  for (const FluidPhase& p : model.fluid.phases)
    if (p.viscosity > 0 || (p.melting_point && p.solid_viscosity > 0)) return true;
  return false;
}

void apply_implicit_fluid_viscosity(const Model& model, State& state, FluidScratch& scratch, Real h) {
  if (model.fluid.viscosity_solver != ViscositySolver::implicit_solve || !fluid_has_viscosity(model)) return;
  FluidState& fluid = state.fluid;
  const bool rough_solids = model.fluid.solid.any_friction;
  if (rough_solids) place_rough_samples(model, state, scratch);
  implicit_solve(model, fluid, scratch, h);
#pragma omp for schedule(static)
  for (Index k = 0; k < fluid.count; ++k) fluid.velocity[k] += scratch.viscous_change[k];
  if (rough_solids) apply_rough_solid_reactions(model, state, scratch, h);
}

}  // namespace moreau
