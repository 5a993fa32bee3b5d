#include "moreau/fem/distributed/mesh_partition.hpp"

#include <fmt/format.h>
#include <metis.h>

#include <algorithm>
#include <mutex>
#include <stdexcept>

namespace moreau {

static_assert(sizeof(idx_t) == sizeof(int), "Debian's METIS uses 32-bit indices");

std::vector<int> partition_nodes(const std::vector<MeshNodes>& meshes, Index node_count, int parts) {
  std::vector<int> owner(static_cast<size_t>(node_count), 0);
  if (parts <= 1 || node_count == 0) return owner;
  const NodeGraph graph = node_graph(meshes, node_count, false);
  std::vector<idx_t> starts(graph.start.begin(), graph.start.end()), adjacent(graph.neighbour.begin(), graph.neighbour.end());
  idx_t vertices = static_cast<idx_t>(node_count), constraints = 1, nparts = parts, cut = 0;
  idx_t options[METIS_NOPTIONS];
  METIS_SetDefaultOptions(options);
  options[METIS_OPTION_SEED] = 1;
  options[METIS_OPTION_NUMBERING] = 0;
  std::vector<idx_t> part(static_cast<size_t>(node_count), 0);
  // METIS seeds one random generator for the whole process: two partitions at once (threads
  // standing in for ranks in the tests) would draw from each other's sequence.
  static std::mutex metis_in_use;
  const std::lock_guard lock(metis_in_use);
  const int status = METIS_PartGraphKway(&vertices, &constraints, starts.data(), adjacent.data(), nullptr, nullptr,
                                         nullptr, &nparts, nullptr, nullptr, options, &cut, part.data());
  if (status != METIS_OK)
    throw std::runtime_error(fmt::format("METIS could not divide {} nodes among {} ranks (status {})", node_count, parts, status));
  std::copy(part.begin(), part.end(), owner.begin());
  return owner;
}

std::vector<std::vector<Index>> cells_of_rank(const std::vector<std::vector<Index>>& colours, const MeshNodes& mesh,
                                              const std::vector<int>& node_owner, int rank) {
  const int nodes = mesh.mesh->nodes_per_cell();
  std::vector<std::vector<Index>> mine(colours.size());
  for (size_t c = 0; c < colours.size(); ++c)
    for (Index e : colours[c]) {
      const Index* cell = mesh.mesh->cell(e);
      if (std::any_of(cell, cell + nodes, [&](Index a) { return node_owner[mesh.node_begin + a] == rank; }))
        mine[c].push_back(e);
    }
  return mine;
}

}  // namespace moreau
