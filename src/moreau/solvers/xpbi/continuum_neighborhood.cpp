#include "moreau/solvers/xpbi/continuum_neighborhood.hpp"

#include <omp.h>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <array>
#include <cmath>

namespace moreau {

void ContinuumNeighborhood::build(const Model& model, const State& state, int threads) {
  const ContinuumModel& continuum = model.continuum;
  const Index n = continuum.size();
  const WendlandKernel kernel_function(continuum.support());
  start.resize(n);
  volume.resize(n);
  clump_distance.resize(n);
  const Real min_distance = model.settings.xpbi.min_distance * continuum.spacing;
  for (Index i = 0; i < n; ++i) {
    start[i] = state.position[continuum.particle[i]];
    volume[i] = continuum.rest_volume[i] * state.continuum.deformation[i].determinant();
  }
  neighbors.build(start, continuum.support(), threads);

  blocks.build(start.data(), n, GridFrame{Vec3::Zero(), 2 * continuum.support()});
  std::array<std::vector<Index>, kTileColors> colour_blocks;
  for (Index c = 0; c < blocks.cell_count(); ++c) {
    const CellCoord& b = blocks.cell_coord(c);
    colour_blocks[(b[0] & 1) | (b[1] & 1) << 1 | (b[2] & 1) << 2].push_back(c);
  }
  sweep_order.clear();
  sweep_batches.clear();
  for (const std::vector<Index>& colour : colour_blocks) {
    for (Index c : colour) {
      for (Index s = blocks.cell_begin(c); s < blocks.cell_begin(c + 1); ++s) sweep_order.push_back(blocks.order()[s]);
      sweep_batches.tile_offsets.push_back(static_cast<Index>(sweep_order.size()));
    }
    sweep_batches.color_tiles.push_back(static_cast<Index>(sweep_batches.tile_offsets.size()) - 1);
  }

  pair_begin.resize(n + 1);
  pair_begin[0] = 0;
  for (Index s = 0; s < n; ++s) pair_begin[s + 1] = pair_begin[s] + neighbors.count(sweep_order[s]);
  neighbor.resize(pair_begin[n]);
  neighbor_particle.resize(pair_begin[n]);
  weighted_gradient.resize(pair_begin[n]);
  kernel.resize(pair_begin[n]);
  gradient_sum.resize(n);
  gradient_metric.resize(n);
  scratch.resize(threads);
#pragma omp parallel num_threads(threads)
  {
    std::vector<KernelNeighbor>& around = scratch[omp_get_thread_num()];
#pragma omp for schedule(static)
    for (Index s = 0; s < n; ++s) {
      const Index i = sweep_order[s];
      const Index* list = neighbors.neighbors(i);
      const Index count = neighbors.count(i), first = pair_begin[s];
      around.resize(count);
      for (Index k = 0; k < count; ++k) around[k] = {start[list[k]] - start[i], volume[list[k]]};
      const Mat3 correction = kernel_correction(kernel_function, around);
      Vec3 sum = Vec3::Zero();
      Mat3 metric = Mat3::Zero();
      for (Index k = 0; k < count; ++k) {
        const Index b = continuum.particle[list[k]];
        const Vec3 g = around[k].volume * corrected_gradient(kernel_function, correction, around[k].offset);
        neighbor[first + k] = list[k];
        neighbor_particle[first + k] = b;
        weighted_gradient[first + k] = g;
        kernel[first + k] = kernel_function.value(around[k].offset.norm());
        sum += g;
        metric.noalias() += model.particle_inv_mass[b] * g * g.transpose();
      }
      gradient_sum[s] = sum;
      gradient_metric[s] = metric;
      // The smallest stretch of F^n: the square root of the smallest eigenvalue of F^T F.
      const Mat3& F = state.continuum.deformation[i];
      Eigen::SelfAdjointEigenSolver<Mat3> stretches;
      stretches.computeDirect(F.transpose() * F, Eigen::EigenvaluesOnly);
      clump_distance[i] = min_distance * std::min<Real>(1, std::sqrt(std::max<Real>(0, stretches.eigenvalues()[0])));
    }
  }
}

}  // namespace moreau
