#include "moreau/fem/distributed/mesh_partition.hpp"

#include <fmt/format.h>
#include <metis.h>

#include <algorithm>
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
  const int status = METIS_PartGraphKway(&vertices, &constraints, starts.data(), adjacent.data(), nullptr, nullptr,
                                         nullptr, &nparts, nullptr, nullptr, options, &cut, part.data());
  if (status != METIS_OK)
    throw std::runtime_error(fmt::format("METIS could not divide {} nodes among {} ranks (status {})", node_count, parts, status));
  std::copy(part.begin(), part.end(), owner.begin());
  return owner;
}

}  // namespace moreau
