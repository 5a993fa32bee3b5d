#include "moreau/fem/solids/solid_partition.hpp"

#include <numeric>

#include "moreau/fem/distributed/mesh_partition.hpp"

namespace moreau {

void distribute_fem_model(FemModel& model, const petsc_plugin::Communicator& ranks) {
  if (ranks.size() <= 1 || model.node_count == 0) return;
  std::vector<MeshNodes> meshes;
  for (const FemSolid& s : model.solids) meshes.push_back({&s.mesh, s.node_begin});
  const std::vector<int> node_owner = partition_nodes(meshes, model.node_count, ranks.size());
  const int rank = ranks.rank();
  auto partition = std::make_shared<SolidPartition>();
  partition->rows = own_rows_by_node(node_owner, model.free_index, model.dim, model.free_count, ranks);
  std::vector<Index> every_dof(static_cast<size_t>(model.dof_count()));
  std::iota(every_dof.begin(), every_dof.end(), Index(0));
  partition->dofs = own_rows_by_node(node_owner, every_dof, model.dim, model.dof_count(), ranks);
  std::vector<int> cell_owner;
  for (const FemSolid& s : model.solids) {
    for (Index e = 0; e < s.mesh.cell_count(); ++e) cell_owner.push_back(node_owner[s.node_begin + s.mesh.cell(e)[0]]);
    partition->colours.push_back(cells_of_rank(s.colours, {&s.mesh, s.node_begin}, node_owner, rank));
    for (const std::vector<Index>& colour : partition->colours.back())
      partition->assembled_cells += static_cast<Index>(colour.size());
  }
  partition->cells = own_items(std::move(cell_owner), ranks);

  std::vector<char> kept_rows(static_cast<size_t>(model.free_count));
  for (Index row = 0; row < model.free_count; ++row) kept_rows[row] = partition->rows.owns(row);
  model.pattern = cell_coupling_pattern(meshes, model.node_count, model.dim, model.free_index, model.free_count, kept_rows);
  for (FemSolid& s : model.solids) s.slots = cell_slots(s.mesh, s.node_begin, model.dim, model.free_index, model.pattern);
  model.partition = std::move(partition);
}

}  // namespace moreau
