#pragma once
// What every XPBI iteration of a substep reads about the continuum's particles, built once at the
// substep's start x^n (Yu et al. 2024, Alg. 1, lines 1-2): each particle's neighbours within the
// kernel support 2 r, its current volume V^n = V^0 det F^n, and per neighbour pair the corrected
// kernel gradient L_p grad W_b (velocity_gradient.hpp) and the kernel value W_b; and the blocks
// that let threads share a Gauss-Seidel sweep (continuum_sweep.hpp).
#include <vector>

#include "moreau/constraints/tile_batches.hpp"
#include "moreau/geometry/cell_grid.hpp"
#include "moreau/geometry/neighbor_search.hpp"
#include "moreau/continuum/velocity_gradient.hpp"
#include "moreau/model/state.hpp"

namespace moreau {

struct ContinuumNeighborhood {
  NeighborSearch neighbors;          // continuum indices (Model::continuum), pairs closer than the support
  std::vector<Vec3> start;           // m, x^n per continuum particle
  std::vector<Real> volume;          // m^3, V^n
  std::vector<Vec3> gradient;        // 1/m^4, L_p grad_{x_p} W(x_p - x_b) per pair (the neighbors' layout)
  std::vector<Real> kernel;          // 1/m^3, W(|x_p - x_b|) per pair
  // m, the anti-clumping distance of each particle: settings.xpbi.min_distance r, shortened by the
  // smallest stretch of F^n where the body is compressed, so that a uniformly compressed lattice
  // (spacing r s) is not pushed apart as if its particles were clumping.
  std::vector<Real> clump_distance;
  // The Gauss-Seidel sweep's order: blocks of edge twice the support, coloured by the parity of
  // their integer coordinates (tile_batches.hpp). Two blocks of one colour have a whole block
  // between them, and a particle's constraint moves only particles closer than the support to it
  // at x^n, so the constraints of two such blocks share no particle.
  CellGrid blocks;
  std::vector<Index> sweep_order;  // continuum indices, block by block, colour after colour
  TileBatches sweep_batches;       // the blocks as tiles of sweep_order
  std::vector<std::vector<KernelNeighbor>> scratch;  // per thread: one particle's neighbours

  /// Rebuilds everything from state.position (x^n) and the deformation gradients F^n.
  void build(const Model& model, const State& state, int threads);

  /// h grad v_i = sum_b V_b^n (d_b - d_i) (L_i grad W_b)^T of continuum particle i, with d = x - x^n
  /// the motion over the substep (x and x_start indexed by global particle).
  Mat3 substep_deformation(const ContinuumModel& continuum, const Vec3* x, const Vec3* x_start, Index i) const {
    const Index* list = neighbors.neighbors(i);
    const Index count = neighbors.count(i), first = neighbors.offset(i);
    const Index p = continuum.particle[i];
    const Vec3 dp = x[p] - x_start[p];
    Mat3 G = Mat3::Zero();
    for (Index k = 0; k < count; ++k) {
      const Index b = continuum.particle[list[k]];
      G.noalias() += (volume[list[k]] * (x[b] - x_start[b] - dp)) * gradient[first + k].transpose();
    }
    return G;
  }
};

}  // namespace moreau
