#pragma once
// A hashed uniform grid over points: cells of edge `cell_size` are hashed into a table of buckets
// and points are counting-sorted by bucket. A query visits the 27 cells around a point, so it finds
// every point closer than cell_size. Buffers are reused across builds (no allocation once warm).
#include <cstdint>
#include <vector>

#include "moreau/math/types.hpp"

namespace moreau {

class SpatialHash {
 public:
  /// Inserts the points x[ids[k]].
  void build(const std::vector<Index>& ids, const Vec3* x, Real cell_size);

  /// Calls visit(id) for every inserted id in the 27 cells around p (each bucket once).
  template <class Visit>
  void for_each_near(const Vec3& p, Visit&& visit) const {
    const Eigen::Vector3i c = cell_of(p);
    std::uint32_t seen[27];
    int seen_count = 0;
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          const std::uint32_t b = bucket_of(c + Eigen::Vector3i(dx, dy, dz));
          bool duplicate = false;
          for (int s = 0; s < seen_count; ++s) duplicate |= seen[s] == b;
          if (duplicate) continue;
          seen[seen_count++] = b;
          for (Index k = bucket_start_[b]; k < bucket_start_[b + 1]; ++k) visit(entries_[k]);
        }
  }

 private:
  Eigen::Vector3i cell_of(const Vec3& p) const {
    return Eigen::Vector3i(static_cast<int>(std::floor(p.x() * inv_cell_)), static_cast<int>(std::floor(p.y() * inv_cell_)),
                           static_cast<int>(std::floor(p.z() * inv_cell_)));
  }
  std::uint32_t bucket_of(const Eigen::Vector3i& c) const {
    // Teschner et al. 2003, "Optimized Spatial Hashing for Collision Detection of Deformable Objects".
    const std::uint32_t h = (static_cast<std::uint32_t>(c.x()) * 73856093u) ^ (static_cast<std::uint32_t>(c.y()) * 19349663u) ^
                            (static_cast<std::uint32_t>(c.z()) * 83492791u);
    return h & mask_;
  }

  Real inv_cell_ = 1;
  std::uint32_t mask_ = 0;
  std::vector<Index> bucket_start_;   // size buckets + 1
  std::vector<Index> entries_;        // ids sorted by bucket
  std::vector<std::uint32_t> entry_bucket_;
};

}  // namespace moreau
