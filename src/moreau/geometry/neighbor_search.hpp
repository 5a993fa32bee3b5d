#pragma once
// All-pairs fixed-radius neighbour lists of one point set, on a CellGrid (cell edge = radius).
// Lists are CSR (offsets + indices) and are built once and reused, e.g. by every solver iteration
// of a step. The build is parallel over cells with OpenMP and does not depend on the thread count:
// each point's list is written in a fixed cell-visit order into a slot fixed by a prefix sum.
// Buffers only grow, so a warm build allocates nothing.
#include <vector>

#include "moreau/geometry/cell_grid.hpp"

namespace moreau {

class NeighborSearch {
 public:
  /// Finds, for every point i, all j != i with |x_i - x_j| < radius. Call from outside any
  /// OpenMP parallel region; uses `threads` threads (0 = the OpenMP default).
  void build(const std::vector<Vec3>& x, Real radius, int threads = 0);

  /// Number of neighbours of point i and the neighbours themselves (indices into x, in z-order of
  /// the cells visited, then by position in the sort).
  Index count(Index i) const { return offsets_[i + 1] - offsets_[i]; }
  const Index* neighbors(Index i) const { return indices_.data() + offsets_[i]; }
  /// Where point i's list starts among all the lists (arrays per pair share this layout).
  Index offset(Index i) const { return offsets_[i]; }
  Index total() const { return offsets_.empty() ? 0 : offsets_.back(); }

  /// The z-order sort of the points: order()[k] is the k-th point along the curve.
  const std::vector<Index>& order() const { return grid_.order(); }

 private:
  CellGrid grid_;
  std::vector<Index> offsets_, indices_;
};

}  // namespace moreau
