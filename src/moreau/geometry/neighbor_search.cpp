#include "moreau/geometry/neighbor_search.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace moreau {

namespace {

constexpr std::uint32_t kMaxCell = (1u << 21) - 1;  // 21 bits per axis

// Spreads the low 21 bits of v so that bit k moves to bit 3k.
std::uint64_t spread_bits(std::uint64_t v) {
  v &= 0x1fffff;
  v = (v | v << 32) & 0x1f00000000ffffULL;
  v = (v | v << 16) & 0x1f0000ff0000ffULL;
  v = (v | v << 8) & 0x100f00f00f00f00fULL;
  v = (v | v << 4) & 0x10c30c30c30c30c3ULL;
  v = (v | v << 2) & 0x1249249249249249ULL;
  return v;
}

}  // namespace

std::uint64_t NeighborSearch::morton_key(std::uint32_t cx, std::uint32_t cy, std::uint32_t cz) {
  return spread_bits(cx) | spread_bits(cy) << 1 | spread_bits(cz) << 2;
}

void NeighborSearch::build(const std::vector<Vec3>& x, Real radius, int threads) {
  const Index n = static_cast<Index>(x.size());
  offsets_.assign(static_cast<size_t>(n) + 1, 0);
  order_.resize(n);
  if (n == 0) return;
  if (!(radius > 0)) throw std::invalid_argument("NeighborSearch: the search radius must be positive");
  const int thread_count = threads > 0 ? threads : omp_get_max_threads();

  // Cells of edge h = radius, counted from one cell below the lowest point so that every
  // neighbour cell index is non-negative.
  Vec3 lo = x[0];
  for (const Vec3& p : x) lo = lo.cwiseMin(p);
  const Real inv_h = 1 / radius;
  auto cell_of = [&](const Vec3& p) {
    const Vec3 c = (p - lo) * inv_h;
    if (!(c.maxCoeff() < kMaxCell - 2))
      throw std::runtime_error(fmt::format("NeighborSearch: the points span more than {} cells of {} m per axis "
                                           "(or are not finite)", kMaxCell - 2, radius));
    return std::array<std::uint32_t, 3>{static_cast<std::uint32_t>(c.x()) + 1, static_cast<std::uint32_t>(c.y()) + 1,
                                        static_cast<std::uint32_t>(c.z()) + 1};
  };

  // Sort the points along the z-order curve (ties by index: deterministic).
  sorted_.resize(n);
  for (Index i = 0; i < n; ++i) {
    const auto c = cell_of(x[i]);
    sorted_[i] = {morton_key(c[0], c[1], c[2]), i};
  }
  std::sort(sorted_.begin(), sorted_.end());
  for (Index k = 0; k < n; ++k) order_[k] = sorted_[k].second;

  // Non-empty cells as runs of equal keys.
  cell_key_.clear();
  cell_begin_.clear();
  cell_coord_.clear();
  for (Index k = 0; k < n; ++k) {
    if (k == 0 || sorted_[k].first != sorted_[k - 1].first) {
      cell_key_.push_back(sorted_[k].first);
      cell_begin_.push_back(k);
      cell_coord_.push_back(cell_of(x[sorted_[k].second]));
    }
  }
  cell_begin_.push_back(n);
  const Index cells = static_cast<Index>(cell_key_.size());
  const Real r2 = radius * radius;

  // Two passes over the cells: count each point's neighbours, then (after a prefix sum) write them.
  auto for_each_pair_in_cell = [&](Index c, auto&& on_pair) {
    std::array<std::pair<Index, Index>, 27> ranges;
    int range_count = 0;
    const auto& cc = cell_coord_[c];
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const std::uint64_t key = morton_key(cc[0] + dx, cc[1] + dy, cc[2] + dz);
          const auto it = std::lower_bound(cell_key_.begin(), cell_key_.end(), key);
          if (it == cell_key_.end() || *it != key) continue;
          const Index other = static_cast<Index>(it - cell_key_.begin());
          ranges[range_count++] = {cell_begin_[other], cell_begin_[other + 1]};
        }
    for (Index a = cell_begin_[c]; a < cell_begin_[c + 1]; ++a) {
      const Index i = sorted_[a].second;
      const Vec3 xi = x[i];
      for (int r = 0; r < range_count; ++r)
        for (Index b = ranges[r].first; b < ranges[r].second; ++b) {
          const Index j = sorted_[b].second;
          if (j != i && (x[j] - xi).squaredNorm() < r2) on_pair(i, j);
        }
    }
  };

#pragma omp parallel for num_threads(thread_count) schedule(static)
  for (Index c = 0; c < cells; ++c) for_each_pair_in_cell(c, [&](Index i, Index) { ++offsets_[i + 1]; });
  for (Index i = 0; i < n; ++i) offsets_[i + 1] += offsets_[i];
  indices_.resize(offsets_[n]);
#pragma omp parallel for num_threads(thread_count) schedule(static)
  for (Index c = 0; c < cells; ++c) {
    // Each point's slots are filled in visit order; a point belongs to exactly one cell, so
    // only this iteration writes them.
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
