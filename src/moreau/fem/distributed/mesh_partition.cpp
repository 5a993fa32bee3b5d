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
  // The node graph in compressed rows (METIS's xadj, adjncy): per node its cell neighbours, sorted.
  std::vector<std::vector<idx_t>> neighbours(static_cast<size_t>(node_count));
  for (const MeshNodes& m : meshes) {
    const int per_cell = m.mesh->nodes_per_cell();
    for (Index e = 0; e < m.mesh->cell_count(); ++e) {
      const Index* cell = m.mesh->cell(e);
      for (int a = 0; a < per_cell; ++a)
        for (int b = 0; b < per_cell; ++b)
          if (a != b) neighbours[m.node_begin + cell[a]].push_back(static_cast<idx_t>(m.node_begin + cell[b]));
    }
  }
  std::vector<idx_t> starts(1, 0), adjacent;
  for (auto& list : neighbours) {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
    adjacent.insert(adjacent.end(), list.begin(), list.end());
    starts.push_back(static_cast<idx_t>(adjacent.size()));
    list = {};
  }
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
