#include "moreau/geometry/cell_grid.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace moreau {

namespace {

constexpr std::int64_t kMaxCells = (std::int64_t{1} << 21) - 1;  // 21 bits per axis in a key
constexpr int kDigitBits = 11;                                   // radix-sort digit

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

CellCoord GridFrame::cell_of(const Vec3& x) const {
  const Vec3 c = ((x - origin) / cell_size).array().floor();
  constexpr Real kLimit = 1e9;
  if (!(c.cwiseAbs().maxCoeff() < kLimit))
    throw std::runtime_error(fmt::format("a point at ({}, {}, {}) is not finite or lies too far from the grid origin",
                                         x.x(), x.y(), x.z()));
  return {static_cast<std::int32_t>(c.x()), static_cast<std::int32_t>(c.y()), static_cast<std::int32_t>(c.z())};
}

std::uint64_t CellGrid::morton_key(std::uint32_t cx, std::uint32_t cy, std::uint32_t cz) {
  return spread_bits(cx) | spread_bits(cy) << 1 | spread_bits(cz) << 2;
}

void CellGrid::build(const Vec3* x, Index n, const GridFrame& frame) {
  frame_ = frame;
  order_.resize(n);
  point_cell_.resize(n);
  key_.resize(n);
  cell_key_.clear();
  cell_begin_.clear();
  cell_coord_.clear();
  if (n == 0) {
    cell_begin_.push_back(0);
    extent_ = {0, 0, 0};
    use_dense_ = false;
    return;
  }

  // Cells and their bounding box.
  CellCoord lo{INT32_MAX, INT32_MAX, INT32_MAX}, hi{INT32_MIN, INT32_MIN, INT32_MIN};
  for (Index i = 0; i < n; ++i) {
    const CellCoord c = frame.cell_of(x[i]);
    point_cell_[i] = c;
    for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], c[a]), hi[a] = std::max(hi[a], c[a]);
  }
  for (int a = 0; a < 3; ++a) {
    if (std::int64_t{hi[a]} - lo[a] >= kMaxCells)
      throw std::runtime_error(fmt::format("the points span more than {} cells of {} m along axis {}; a particle "
                                           "has probably left the scene",
                                           kMaxCells, frame.cell_size, "xyz"[a]));
    extent_[a] = hi[a] - lo[a] + 1;
  }
  lo_ = lo;

  // Keys relative to the box corner; sort by the bits that vary (stable LSD radix sort).
  std::uint64_t all_bits = 0;
  for (Index i = 0; i < n; ++i) {
    const CellCoord& c = point_cell_[i];
    key_[i] = morton_key(c[0] - lo[0], c[1] - lo[1], c[2] - lo[2]);
    all_bits |= key_[i];
    order_[i] = i;
  }
  int bits = 0;
  while (bits < 64 && (all_bits >> bits) != 0) ++bits;
  key_scratch_.resize(n);
  order_scratch_.resize(n);
  histogram_.resize(std::size_t{1} << kDigitBits);
  for (int shift = 0; shift < bits; shift += kDigitBits) {
    std::fill(histogram_.begin(), histogram_.end(), 0);
    const std::uint64_t mask = (std::uint64_t{1} << kDigitBits) - 1;
    for (Index i = 0; i < n; ++i) ++histogram_[(key_[i] >> shift) & mask];
    Index sum = 0;
    for (Index& h : histogram_) {
      const Index count = h;
      h = sum;
      sum += count;
    }
    for (Index i = 0; i < n; ++i) {
      const Index slot = histogram_[(key_[i] >> shift) & mask]++;
      key_scratch_[slot] = key_[i];
      order_scratch_[slot] = order_[i];
    }
    key_.swap(key_scratch_);
    order_.swap(order_scratch_);
  }

  // Non-empty cells as runs of equal keys.
  for (Index k = 0; k < n; ++k) {
    if (k == 0 || key_[k] != key_[k - 1]) {
      cell_key_.push_back(key_[k]);
      cell_begin_.push_back(k);
      cell_coord_.push_back(point_cell_[order_[k]]);
    }
  }
  cell_begin_.push_back(n);

  // Dense lookup table when the box is at most a few cells per point.
  const std::int64_t box = std::int64_t{extent_[0]} * extent_[1] * extent_[2];
  use_dense_ = box <= std::max<std::int64_t>(8 * std::int64_t{n}, 1 << 16);
  if (use_dense_) {
    dense_.assign(static_cast<std::size_t>(box), -1);
    for (Index c = 0; c < cell_count(); ++c) {
      const CellCoord& cc = cell_coord_[c];
      dense_[(std::int64_t{cc[2] - lo[2]} * extent_[1] + (cc[1] - lo[1])) * extent_[0] + (cc[0] - lo[0])] = c;
    }
  }
}

Index CellGrid::find_cell(const CellCoord& c) const {
  std::int32_t d[3];
  for (int a = 0; a < 3; ++a) {
    d[a] = c[a] - lo_[a];
    if (d[a] < 0 || d[a] >= extent_[a]) return -1;
  }
  if (use_dense_) return dense_[(std::int64_t{d[2]} * extent_[1] + d[1]) * extent_[0] + d[0]];
  const std::uint64_t key = morton_key(d[0], d[1], d[2]);
  const auto it = std::lower_bound(cell_key_.begin(), cell_key_.end(), key);
  if (it == cell_key_.end() || *it != key) return -1;
  return static_cast<Index>(it - cell_key_.begin());
}

int CellGrid::neighbor_ranges(const CellCoord& c, CellRange* out) const {
  int count = 0;
  for (int dz = -1; dz <= 1; ++dz)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const Index cell = find_cell({c[0] + dx, c[1] + dy, c[2] + dz});
        if (cell >= 0) out[count++] = {cell_begin_[cell], cell_begin_[cell + 1]};
      }
  return count;
}

int CellGrid::ranges_ahead(const CellCoord& c, CellRange* out) const {
  int count = 0;
  for (int dz = 0; dz <= 1; ++dz)
    for (int dy = dz > 0 ? -1 : 0; dy <= 1; ++dy)
      for (int dx = (dz > 0 || dy > 0) ? -1 : 1; dx <= 1; ++dx) {
        const Index cell = find_cell({c[0] + dx, c[1] + dy, c[2] + dz});
        if (cell >= 0) out[count++] = {cell_begin_[cell], cell_begin_[cell + 1]};
      }
  return count;
}

int CellGrid::ranges_near(const Vec3& x, Real radius, CellRange* out) const {
  const CellCoord c = frame_.cell_of(x);
  const Real h = frame_.cell_size;
  const Vec3 local = (x - frame_.origin) / h;  // in cells
  int count = 0;
  // The squared distance from x to cell (i) along one axis, in cells.
  auto gap = [&](int axis, int i) {
    const Real d = std::max({Real(0), i - local[axis], local[axis] - (i + 1)});
    return d * d;
  };
  const Real reach2 = (radius / h) * (radius / h);
  for (int dz = -2; dz <= 2; ++dz) {
    const Real gz = gap(2, c[2] + dz);
    if (gz > reach2) continue;
    for (int dy = -2; dy <= 2; ++dy) {
      const Real gy = gz + gap(1, c[1] + dy);
      if (gy > reach2) continue;
      for (int dx = -2; dx <= 2; ++dx) {
        if (gy + gap(0, c[0] + dx) > reach2) continue;
        const Index cell = find_cell({c[0] + dx, c[1] + dy, c[2] + dz});
        if (cell >= 0) out[count++] = {cell_begin_[cell], cell_begin_[cell + 1]};
      }
    }
  }
  return count;
}

}  // namespace moreau
