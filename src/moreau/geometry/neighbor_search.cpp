#include "moreau/geometry/neighbor_search.hpp"

#include <omp.h>

#include <stdexcept>

namespace moreau {

void NeighborSearch::build(const std::vector<Vec3>& x, Real radius, int threads) {
  const Index n = static_cast<Index>(x.size());
  offsets_.assign(static_cast<size_t>(n) + 1, 0);
  if (!(radius > 0)) throw std::invalid_argument("NeighborSearch: the search radius must be positive");
  grid_.build(x.data(), n, GridFrame{Vec3::Zero(), radius});
  if (n == 0) return;
  const int thread_count = threads > 0 ? threads : omp_get_max_threads();
  const std::vector<Index>& order = grid_.order();
  const Index cells = grid_.cell_count();
  const Real r2 = radius * radius;

  // Visits every pair (i, j), |x_i - x_j| < radius, with i in cell c, in a fixed order.
  auto for_each_pair_in_cell = [&](Index c, auto&& on_pair) {
    CellRange ranges[27];
    const int range_count = grid_.neighbor_ranges(grid_.cell_coord(c), ranges);
    for (Index a = grid_.cell_begin(c); a < grid_.cell_begin(c + 1); ++a) {
      const Index i = order[a];
      const Vec3 xi = x[i];
      for (int r = 0; r < range_count; ++r)
        for (Index b = ranges[r].first; b < ranges[r].second; ++b) {
          const Index j = order[b];
          if (j != i && (x[j] - xi).squaredNorm() < r2) on_pair(i, j);
        }
    }
  };

  // Count each point's neighbours, prefix-sum, then write them.
#pragma omp parallel for num_threads(thread_count) schedule(static)
  for (Index c = 0; c < cells; ++c) for_each_pair_in_cell(c, [&](Index i, Index) { ++offsets_[i + 1]; });
  for (Index i = 0; i < n; ++i) offsets_[i + 1] += offsets_[i];
  indices_.resize(offsets_[n]);
#pragma omp parallel for num_threads(thread_count) schedule(static)
  for (Index c = 0; c < cells; ++c) {
    // A point belongs to exactly one cell, so only this iteration writes its slots.
    Index cursor_point = -1, cursor = 0;
    for_each_pair_in_cell(c, [&](Index i, Index j) {
      if (i != cursor_point) {
        cursor_point = i;
        cursor = offsets_[i];
      }
      indices_[cursor++] = j;
    });
  }
}

}  // namespace moreau
