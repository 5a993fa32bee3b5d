#pragma once
// A FEM solid model divided among the ranks of a distributed run. Each rank assembles the cells
// that touch its nodes, which completes its own rows of every force and tangent; the tangent keeps
// only those rows (the distributed solver reads no others). The forces on all degrees of freedom
// and the cells' energies and validity are then gathered from their owners, so every rank holds
// the same bits as one process would and takes the same Newton decisions.
#include <memory>
#include <vector>

#include "moreau/fem/distributed/row_ownership.hpp"
#include "moreau/fem/solids/fem_model.hpp"

namespace moreau {

struct SolidPartition {
  RowOwnership rows;   // the free unknowns (the tangent's rows), by their nodes' ranks
  RowOwnership dofs;   // every degree of freedom, prescribed ones included, by their nodes' ranks
  RowOwnership cells;  // every cell of every solid, solid after solid, by the rank of its first node
                       // (which assembles it)
  std::vector<std::vector<std::vector<Index>>> colours;  // per solid, this rank's cells in its colours
  Index assembled_cells = 0;                            // this rank's, over all solids
};

/// Divides a finalized model among the ranks (METIS on the node graph of all solids), and makes its
/// pattern and cell slots this rank's rows only. A model without degrees of freedom stays whole.
void distribute_fem_model(FemModel& model, const petsc_plugin::Communicator& ranks);

}  // namespace moreau
