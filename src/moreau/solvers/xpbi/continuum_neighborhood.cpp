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
  // The live particles (State::live: an emitter's unreleased ones take no part), in continuum
  // order; the searches below index them by their place in this list.
  live.clear();
  for (Index i = 0; i < n; ++i)
    if (state.live(continuum.particle[i])) live.push_back(i);
  const Index m = static_cast<Index>(live.size());
  live_start.clear();
  if (m < n)
    for (Index i : live) live_start.push_back(start[i]);
  const std::vector<Vec3>& points = m < n ? live_start : start;  // every particle live: x^n itself
  neighbors.build(points, continuum.support(), threads);

  blocks.build(points.data(), m, GridFrame{Vec3::Zero(), 2 * continuum.support()});
  std::array<std::vector<Index>, kTileColors> colour_blocks;
  for (Index c = 0; c < blocks.cell_count(); ++c) {
    const CellCoord& b = blocks.cell_coord(c);
    colour_blocks[(b[0] & 1) | (b[1] & 1) << 1 | (b[2] & 1) << 2].push_back(c);
  }
  sweep_order.clear();
  sweep_live.clear();
  sweep_batches.clear();
  for (const std::vector<Index>& colour : colour_blocks) {
    for (Index c : colour) {
      for (Index s = blocks.cell_begin(c); s < blocks.cell_begin(c + 1); ++s) {
        sweep_live.push_back(blocks.order()[s]);
        sweep_order.push_back(live[blocks.order()[s]]);
      }
      sweep_batches.tile_offsets.push_back(static_cast<Index>(sweep_order.size()));
    }
    sweep_batches.color_tiles.push_back(static_cast<Index>(sweep_batches.tile_offsets.size()) - 1);
  }

  pair_begin.resize(m + 1);
  pair_begin[0] = 0;
  for (Index s = 0; s < m; ++s) pair_begin[s + 1] = pair_begin[s] + neighbors.count(sweep_live[s]);
  neighbor.resize(pair_begin[m]);
  neighbor_particle.resize(pair_begin[m]);
  weighted_gradient.resize(pair_begin[m]);
  kernel.resize(pair_begin[m]);
  gradient_sum.resize(m);
  gradient_metric.resize(m);
  scratch.resize(threads);
#pragma omp parallel num_threads(threads)
  {
    std::vector<KernelNeighbor>& around = scratch[omp_get_thread_num()];
#pragma omp for schedule(static)
    for (Index s = 0; s < m; ++s) {
      const Index i = sweep_order[s];
      const Index* list = neighbors.neighbors(sweep_live[s]);
      const Index count = neighbors.count(sweep_live[s]), first = pair_begin[s];
      around.resize(count);
      for (Index k = 0; k < count; ++k) around[k] = {start[live[list[k]]] - start[i], volume[live[list[k]]]};
      const Mat3 correction = kernel_correction(kernel_function, around);
      Vec3 sum = Vec3::Zero();
      Mat3 metric = Mat3::Zero();
      for (Index k = 0; k < count; ++k) {
        const Index j = live[list[k]], b = continuum.particle[j];
        const Vec3 g = around[k].volume * corrected_gradient(kernel_function, correction, around[k].offset);
        neighbor[first + k] = j;
        neighbor_particle[first + k] = b;
        weighted_gradient[first + k] = g;
        kernel[first + k] = kernel_function.value(around[k].offset.norm());
        sum += g;
        metric.noalias() += moving_inverse_mass(model, state, b) * g * g.transpose();
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
