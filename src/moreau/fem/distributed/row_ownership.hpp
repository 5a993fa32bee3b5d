#pragma once
// Which rank owns each row (free unknown) of a distributed FEM system. A rank assembles its own rows
// completely (every cell that touches one of its nodes) and hands only them to the distributed
// solver; the residual's rows are then gathered so that every rank holds the whole residual and
// takes the same Newton decisions.
#include <vector>

#include "moreau/fem/petsc/petsc_plugin_api.hpp"
#include "moreau/math/types.hpp"

namespace moreau {

struct RowOwnership {
  const petsc_plugin::Communicator* world = nullptr;
  int rank = 0;
  std::vector<int> owner;      // per item (a free unknown, a dof, a cell), its rank
  std::vector<int> counts;     // per rank, how many it owns
  std::vector<Index> by_rank;  // the free unknowns, rank 0's first, each rank's in order

  bool owns(Index row) const { return owner[row] == rank; }
  /// v (one entry per free unknown) is right in this rank's rows; afterwards every entry is right,
  /// on every rank (the rows gathered from their owners).
  void complete(VectorX& v) const;
};

/// Items (rows, cells, ...) owned by the given ranks, one entry of `owner` per item.
RowOwnership own_items(std::vector<int> owner, const petsc_plugin::Communicator& world);

/// Rows owned by their nodes' ranks: node_owner per node, dofs node-major with `fields` per node,
/// free_index per dof (-1 if prescribed).
RowOwnership own_rows_by_node(const std::vector<int>& node_owner, const std::vector<Index>& free_index, int fields,
                              Index free_count, const petsc_plugin::Communicator& world);

}  // namespace moreau
