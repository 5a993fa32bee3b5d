#include "moreau/geometry/spatial_hash.hpp"

#include <algorithm>

namespace moreau {

void SpatialHash::build(const std::vector<Index>& ids, const Vec3* x, Real cell_size) {
  inv_cell_ = 1.0 / cell_size;
  std::uint32_t buckets = 1024;
  while (buckets < 2 * ids.size()) buckets <<= 1;
  mask_ = buckets - 1;
  bucket_start_.assign(buckets + 1, 0);
  entry_bucket_.resize(ids.size());
  for (size_t k = 0; k < ids.size(); ++k) {
    entry_bucket_[k] = bucket_of(cell_of(x[ids[k]]));
    ++bucket_start_[entry_bucket_[k] + 1];
  }
  for (std::uint32_t b = 0; b < buckets; ++b) bucket_start_[b + 1] += bucket_start_[b];
  entries_.resize(ids.size());
  // Fill in input order within a bucket (stable), using bucket_start_ shifted by one as cursors.
  std::vector<Index>& cursor = bucket_start_;
  for (size_t k = 0; k < ids.size(); ++k) entries_[cursor[entry_bucket_[k]]++] = ids[k];
  // The cursors now hold each bucket's end; shift back to starts.
  for (std::uint32_t b = buckets; b > 0; --b) bucket_start_[b] = bucket_start_[b - 1];
  bucket_start_[0] = 0;
}

}  // namespace moreau
