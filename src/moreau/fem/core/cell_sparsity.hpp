#pragma once
// What every FEM system on a mesh needs besides its physics: cell colours for race-free parallel
// assembly, the sparsity of the free-dof matrix and, per cell, where each of its local entries
// lands in that matrix's value array. Dofs are node-major with `fields` per node
// (global dof = (node_begin + node) * fields + field); `free_index` maps a dof to its free number
// or -1 when it is prescribed. Used by the solids (fem_model) and the flow (navier_stokes).
#include <Eigen/Sparse>
#include <omp.h>

#include <vector>

#include "moreau/fem/core/fem_mesh.hpp"

namespace moreau {

using SparseMatrix = Eigen::SparseMatrix<Real, Eigen::ColMajor, int>;

/// Greedy colouring: no two cells of a colour share a node (unbounded number of colours).
std::vector<std::vector<Index>> colour_cells(const FemMesh& mesh);

/// A mesh whose nodes are numbered from node_begin in its problem's node numbering.
struct MeshNodes {
  const FemMesh* mesh = nullptr;
  Index node_begin = 0;
};

/// Which nodes share a cell, in compressed rows: the neighbours of node a are
/// neighbour[start[a]] .. neighbour[start[a + 1] - 1], sorted; a node is its own neighbour only
/// if `with_self`.
struct NodeGraph {
  std::vector<Index> start, neighbour;
};
NodeGraph node_graph(const std::vector<MeshNodes>& meshes, Index node_count, bool with_self);

/// The sparsity of the free-dof matrix of cells on these meshes: an entry (zero) for every
/// (free row, free column) pair of dofs of a common cell, built column by column from the node
/// graph. `kept_rows`, if not empty, has one flag per free dof and leaves out the rows without it
/// (a distributed system keeps its rank's rows). Free dofs must be numbered in dof order
/// (number_free_dofs does).
SparseMatrix cell_coupling_pattern(const std::vector<MeshNodes>& meshes, Index node_count, int fields,
                                   const std::vector<Index>& free_index, Index free_count,
                                   const std::vector<char>& kept_rows = {});

/// Per cell and local (row, column) pair, row-major, the position in `pattern`'s value array, or
/// -1 when either dof is prescribed or the pattern leaves the pair out (a distributed system keeps
/// its rank's rows only). `pattern` must be compressed.
std::vector<Index> cell_slots(const FemMesh& mesh, Index node_begin, int fields, const std::vector<Index>& free_index,
                              const SparseMatrix& pattern);

/// The free components of a vector over all dofs, in free order.
Eigen::VectorXd gather_free(const std::vector<Index>& free_index, Index free_count, const Eigen::VectorXd& full);
/// full[d] += free[free_index[d]] for every free dof d.
void add_free(const std::vector<Index>& free_index, const Eigen::VectorXd& free, Eigen::VectorXd& full);

/// Calls visit(e) for every cell, colour by colour, the cells of one colour in parallel: they
/// share no node, so visit may add into the nodes' global entries without races, and every entry
/// receives its cells in colour order whatever the thread count (bit-identical results).
template <class Visit>
void for_each_cell_by_colour(const std::vector<std::vector<Index>>& colours, int threads, Visit visit) {
  for (const std::vector<Index>& colour : colours) {
    const Index count = static_cast<Index>(colour.size());
#pragma omp parallel for schedule(static) num_threads(threads > 0 ? threads : omp_get_max_threads())
    for (Index i = 0; i < count; ++i) visit(colour[i]);
  }
}

}  // namespace moreau
