#pragma once
// The division of a FEM problem's nodes among the ranks of a distributed run.
#include <vector>

#include "moreau/fem/core/cell_sparsity.hpp"

namespace moreau {

/// Per node of the problem (node_count of them, covering the meshes'), the rank that owns it, in
/// 0 .. parts - 1: METIS's multilevel k-way partition of the graph whose edges join the nodes of
/// a common cell (Karypis & Kumar 1998, SIAM J. Sci. Comput. 20), which balances the nodes and
/// minimises the edges cut, the matrix entries that couple two ranks. METIS's random choices use
/// a fixed seed, so every rank computes the same partition. Throws std::runtime_error if METIS fails.
std::vector<int> partition_nodes(const std::vector<MeshNodes>& meshes, Index node_count, int parts);

/// The cells a rank assembles: those with a node it owns (node_owner per node of the problem; the
/// mesh's nodes numbered from node_begin), which complete its rows. Kept in the given colours,
/// in their order, so its rows receive their cells in the same order as on one process.
std::vector<std::vector<Index>> cells_of_rank(const std::vector<std::vector<Index>>& colours, const MeshNodes& mesh,
                                              const std::vector<int>& node_owner, int rank);

}  // namespace moreau
