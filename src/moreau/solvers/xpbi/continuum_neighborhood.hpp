#pragma once
// What every XPBI iteration of a substep reads about the continuum's particles, built once at the
// substep's start x^n (Yu et al. 2024, Alg. 1, lines 1-2): each particle's neighbours within the
// kernel support 2 r, its current volume V^n = V^0 det F^n, and per neighbour pair the corrected
// kernel gradient L_p grad W_b (velocity_gradient.hpp) and the kernel value W_b; and the blocks
// that let threads share a Gauss-Seidel sweep (continuum_sweep.hpp). Everything an iteration can
// compute once per substep is computed here, so that an iteration makes two passes over a
// particle's pairs: one for its trial F, one to apply its correction.
#include <vector>

#include "moreau/constraints/tile_batches.hpp"
#include "moreau/geometry/cell_grid.hpp"
#include "moreau/geometry/neighbor_search.hpp"
#include "moreau/continuum/velocity_gradient.hpp"
#include "moreau/model/state.hpp"

namespace moreau {

struct ContinuumNeighborhood {
  std::vector<Index> live;           // continuum indices of the live particles (State::live), in order
  std::vector<Vec3> live_start;      // m, x^n of each of them, when some particle is not live
  NeighborSearch neighbors;          // places in `live`, pairs closer than the support
  std::vector<Vec3> start;           // m, x^n per continuum particle
  std::vector<Real> volume;          // m^3, V^n
  // m, the anti-clumping distance of each particle: settings.xpbi.min_distance r, shortened by the
  // smallest stretch of F^n where the body is compressed, so that a uniformly compressed lattice
  // (spacing r s) is not pushed apart as if its particles were clumping.
  std::vector<Real> clump_distance;

  // The Gauss-Seidel sweep's order: blocks of edge twice the support, coloured by the parity of
  // their integer coordinates (tile_batches.hpp). Two blocks of one colour have a whole block
  // between them, and a particle's constraint moves only particles closer than the support to it
  // at x^n, so the constraints of two such blocks share no particle.
  CellGrid blocks;
  std::vector<Index> sweep_order;  // continuum indices of the live particles, block by block, colour after colour
  std::vector<Index> sweep_live;   // their places in `live`
  TileBatches sweep_batches;       // the blocks as tiles of sweep_order

  // What the iterations read, laid out in the sweep's order so that a sweep streams through it:
  // the pairs of the particle at sweep position s are [pair_begin[s], pair_begin[s + 1]).
  // Per pair: the neighbour (continuum index) and its particle (Model index; kept beside it so that
  // the iterations' loops, which read only positions, need no second lookup), the corrected kernel
  // gradient weighted by the neighbour's volume, V_b^n L_p grad_{x_p} W(x_p - x_b) (1/m), and the
  // kernel value W(|x_p - x_b|) (1/m^3).
  std::vector<Index> pair_begin;
  std::vector<Index> neighbor;
  std::vector<Index> neighbor_particle;
  std::vector<Vec3> weighted_gradient;
  std::vector<Real> kernel;
  // Per sweep position, sums over the particle's pairs that do not change within the substep:
  // S_p = sum_b V_b L_p grad W_b (1/m), so that the particle's own gradient is -A S_p, and the
  // metric M_p = sum_b w_b (V_b L_p grad W_b)(V_b L_p grad W_b)^T (1/(kg m^2)), so that the
  // constraint's sum_b w_b |A V_b L_p grad W_b|^2 is the trace of A M_p A^T.
  std::vector<Vec3> gradient_sum;
  std::vector<Mat3> gradient_metric;
  std::vector<std::vector<KernelNeighbor>> scratch;  // per thread: one particle's neighbours

  /// Rebuilds everything from state.position (x^n), the deformation gradients F^n and the
  /// particles' inverse masses (0 in an emitter's nozzle: moving_inverse_mass).
  void build(const Model& model, const State& state, int threads);

  /// The live particles: the sweep's positions are [0, live_count()).
  Index live_count() const { return static_cast<Index>(sweep_order.size()); }

  /// h grad v_i = sum_b V_b^n (d_b - d_i) (L_i grad W_b)^T of the particle i at sweep position s,
  /// with d = x - x^n the motion over the substep (x and x_start indexed by global particle),
  /// evaluated as sum_b d_b (V_b L_i grad W_b)^T - d_i S_i^T.
  Mat3 substep_deformation(const ContinuumModel& continuum, const Vec3* x, const Vec3* x_start, Index s) const {
    const Index begin = pair_begin[s], end = pair_begin[s + 1];
    const Index p = continuum.particle[sweep_order[s]];
    // The columns summed in locals, which the compiler keeps in registers.
    const Vec3 dp = x_start[p] - x[p];
    Vec3 c0 = gradient_sum[s][0] * dp, c1 = gradient_sum[s][1] * dp, c2 = gradient_sum[s][2] * dp;
    for (Index k = begin; k < end; ++k) {
      const Index b = neighbor_particle[k];
      const Vec3 d = x[b] - x_start[b];
      const Vec3& g = weighted_gradient[k];
      c0 += g[0] * d;
      c1 += g[1] * d;
      c2 += g[2] * d;
    }
    Mat3 G;
    G << c0, c1, c2;
    return G;
  }
};

}  // namespace moreau
