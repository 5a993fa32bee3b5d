#pragma once
// A compact uniform grid for fixed-radius neighbour queries (fluids, granular media, XPBI).
//
// Points are sorted by the z-order (Morton) key of their cell (Ihmsen et al. 2011, "A parallel
// SPH implementation on multi-core CPUs": z-index sort), so the points of one cell are contiguous
// and cells close in space are close in memory. The sort is a stable LSD radix sort over the key
// bits that actually vary, so ties keep their input order and the result is deterministic.
// Only non-empty cells are stored. A cell is found from its integer coordinates through a dense
// table over the points' bounding box of cells when that box is small (the usual case: one
// lookup), else by binary search over the sorted keys.
//
// Several grids built with the same GridFrame share integer cell coordinates, so the cells of a
// fluid grid can look up their neighbours in a boundary grid built elsewhere.
#include <array>
#include <cstdint>
#include <utility>
#include <tuple>
#include <vector>

#include "moreau/math/types.hpp"

namespace moreau {

using CellCoord = std::array<std::int32_t, 3>;

/// Cell size and origin shared by grids that are queried against each other.
struct GridFrame {
  Vec3 origin = Vec3::Zero();  // m
  Real cell_size = 1;          // m

  CellCoord cell_of(const Vec3& x) const;
};

/// Sorted positions [first, second) of one cell.
using CellRange = std::pair<Index, Index>;

class CellGrid {
 public:
  /// Sorts the points x[0..n) by cell. Throws std::runtime_error if a point is not finite or the
  /// points span more than 2^21 cells along an axis.
  void build(const Vec3* x, Index n, const GridFrame& frame);

  const GridFrame& frame() const { return frame_; }
  Index point_count() const { return static_cast<Index>(order_.size()); }
  /// order()[k] is the input index of the k-th point in z-order.
  const std::vector<Index>& order() const { return order_; }

  Index cell_count() const { return static_cast<Index>(cell_coord_.size()); }
  /// Cell c holds the sorted positions [cell_begin(c), cell_begin(c + 1)).
  Index cell_begin(Index c) const { return cell_begin_[c]; }
  const CellCoord& cell_coord(Index c) const { return cell_coord_[c]; }
  /// The Morton key of cell c (its coordinates taken from the occupied cells' lowest corner);
  /// cells are sorted by it.
  std::uint64_t cell_key(Index c) const { return cell_key_[c]; }

  /// The cell at integer coordinates c, or -1 if it holds no point.
  Index find_cell(const CellCoord& c) const;
  /// Writes to out[0..27) the ranges of the non-empty cells among the 27 around c; returns their count.
  int neighbor_ranges(const CellCoord& c, CellRange* out) const;
  /// Writes to out[0..13) the ranges of the non-empty cells among the 13 neighbours of c that lie
  /// ahead of it (offset (dx, dy, dz) with dz > 0, or dz = 0 and dy > 0, or dz = dy = 0 and dx > 0):
  /// visiting them from every cell visits each pair of neighbouring cells once.
  int ranges_ahead(const CellCoord& c, CellRange* out) const;
  /// Writes to `out` the ranges of the non-empty cells that reach within `radius` of x (at most 2
  /// cells' width: 125 cells); returns their count.
  int ranges_near(const Vec3& x, Real radius, CellRange* out) const;

  /// The 63-bit Morton key of non-negative cell offsets (21 bits per axis, interleaved x, y, z).
  static std::uint64_t morton_key(std::uint32_t cx, std::uint32_t cy, std::uint32_t cz);

  /// Every member, for checkpoints (io/binary_archive.hpp): a restored grid answers as this one.
  auto archive_members() { return std::tie(frame_, lo_, extent_, order_, point_cell_, key_, key_scratch_, order_scratch_, histogram_, cell_key_, cell_begin_, cell_coord_, dense_, use_dense_); }
  auto archive_members() const { return std::tie(frame_, lo_, extent_, order_, point_cell_, key_, key_scratch_, order_scratch_, histogram_, cell_key_, cell_begin_, cell_coord_, dense_, use_dense_); }

 private:
  GridFrame frame_;
  CellCoord lo_{0, 0, 0}, extent_{0, 0, 0};  // bounding box of the occupied cells
  std::vector<Index> order_;
  std::vector<CellCoord> point_cell_;
  std::vector<std::uint64_t> key_, key_scratch_;
  std::vector<Index> order_scratch_;
  std::vector<Index> histogram_;
  std::vector<std::uint64_t> cell_key_;
  std::vector<Index> cell_begin_;
  std::vector<CellCoord> cell_coord_;
  std::vector<Index> dense_;  // cell id per cell of the bounding box, -1 when empty (if small enough)
  bool use_dense_ = false;
};

}  // namespace moreau
