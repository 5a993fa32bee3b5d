#pragma once
// Fixed-radius neighbour search for particle methods (fluids, granular media, XPBI).
//
// A compact uniform grid with cells of edge h (the search radius): points are sorted by the
// z-order (Morton) key of their cell, so the points of one cell are contiguous and nearby cells
// are close in memory; only non-empty cells are stored (sorted keys, looked up by binary search).
// `order()` is that sort: a caller that permutes its particle arrays by it gets cache-friendly
// access in every later loop. Neighbour lists are built once (CSR: offsets + indices) and reused
// by all solver iterations of a step. The build is parallel over cells with OpenMP and its result
// does not depend on the thread count: each point's list is written in a fixed cell-visit order
// into a slot fixed by a prefix sum. Buffers only grow, so a warm build allocates nothing.
#include <cstdint>
#include <vector>

#include "moreau/math/types.hpp"

namespace moreau {

class NeighborSearch {
 public:
  /// Finds, for every point i, all j != i with |x_i - x_j| < radius. Call from outside any
  /// OpenMP parallel region; uses `threads` threads (0 = the OpenMP default).
  void build(const std::vector<Vec3>& x, Real radius, int threads = 0);

  /// Number of neighbours of point i and the neighbours themselves (indices into x, ascending
  /// in the sorted order of the cells visited, then by position in the sort).
  Index count(Index i) const { return offsets_[i + 1] - offsets_[i]; }
  const Index* neighbors(Index i) const { return indices_.data() + offsets_[i]; }
  Index total() const { return offsets_.empty() ? 0 : offsets_.back(); }

  /// The z-order sort of the points: order()[k] is the k-th point along the curve.
  const std::vector<Index>& order() const { return order_; }

  /// The 63-bit Morton key of an integer cell (21 bits per axis, interleaved x, y, z).
  static std::uint64_t morton_key(std::uint32_t cx, std::uint32_t cy, std::uint32_t cz);

 private:
  std::vector<std::uint64_t> point_key_;     // cell key of each point
  std::vector<std::pair<std::uint64_t, Index>> sorted_;  // (key, point) in z-order
  std::vector<Index> order_;
  std::vector<std::uint64_t> cell_key_;      // non-empty cells, ascending key
  std::vector<Index> cell_begin_;            // cell c holds sorted_[cell_begin_[c], cell_begin_[c+1])
  std::vector<std::array<std::uint32_t, 3>> cell_coord_;
  std::vector<Index> offsets_, indices_;
};

}  // namespace moreau
