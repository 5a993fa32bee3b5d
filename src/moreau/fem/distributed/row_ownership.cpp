#include "moreau/fem/distributed/row_ownership.hpp"

namespace moreau {

RowOwnership own_items(std::vector<int> owner, const petsc_plugin::Communicator& world) {
  RowOwnership rows;
  rows.world = &world;
  rows.rank = world.rank();
  rows.owner = std::move(owner);
  rows.counts.assign(static_cast<size_t>(world.size()), 0);
  for (int o : rows.owner) ++rows.counts[o];
  std::vector<Index> next(rows.counts.size(), 0);
  for (size_t r = 1; r < next.size(); ++r) next[r] = next[r - 1] + rows.counts[r - 1];
  rows.by_rank.resize(rows.owner.size());
  for (size_t i = 0; i < rows.owner.size(); ++i) rows.by_rank[next[rows.owner[i]]++] = static_cast<Index>(i);
  return rows;
}

RowOwnership own_rows_by_node(const std::vector<int>& node_owner, const std::vector<Index>& free_index, int fields,
                              Index free_count, const petsc_plugin::Communicator& world) {
  std::vector<int> owner(static_cast<size_t>(free_count), 0);
  for (size_t d = 0; d < free_index.size(); ++d)
    if (free_index[d] >= 0) owner[free_index[d]] = node_owner[d / fields];
  return own_items(std::move(owner), world);
}

void RowOwnership::complete(VectorX& v) const {
  Index first = 0;
  for (int r = 0; r < rank; ++r) first += counts[r];
  std::vector<double> mine(static_cast<size_t>(counts[rank])), all(by_rank.size());
  for (int i = 0; i < counts[rank]; ++i) mine[i] = v[by_rank[first + i]];
  world->all_gather(mine.data(), counts.data(), all.data());
  for (size_t i = 0; i < by_rank.size(); ++i) v[by_rank[i]] = all[i];
}

}  // namespace moreau
