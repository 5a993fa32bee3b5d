// The division of a FEM problem among MPI ranks: METIS's node partition (balanced, the same on
// every call, a short interface on a structured mesh) and the rows' owners, whose gathered
// residual every rank must read in the same order.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "moreau/fem/distributed/mesh_partition.hpp"
#include "moreau/fem/distributed/row_ownership.hpp"

namespace moreau {
namespace {

TEST(MeshPartition, BalancesNodesAndCutsAStructuredGridAlongAShortInterface) {
  const FemMesh mesh = make_rectangle_mesh(Vec2(0, 0), Vec2(1, 1), {32, 32}, ElementType::quad4);
  for (int parts : {2, 3, 4}) {
    const std::vector<int> owner = partition_nodes({{&mesh, 0}}, mesh.node_count(), parts);
    ASSERT_EQ(owner.size(), static_cast<size_t>(mesh.node_count()));
    std::vector<int> count(parts, 0);
    for (int o : owner) ++count[o];
    // METIS's default load imbalance for k-way partitions is 3 %.
    for (int c : count) EXPECT_LE(c, 1.03 * mesh.node_count() / parts + 1) << parts << " parts";
    // Cells with nodes of several ranks lie along the interfaces: a straight cut across the 32 x 32
    // grid crosses 32 cells; a partition into k parts needs about (k - 1) such cuts. Allowing twice
    // that catches a scattered partition (random owners cut almost every cell).
    int cut_cells = 0;
    for (Index e = 0; e < mesh.cell_count(); ++e) {
      std::set<int> ranks;
      for (int a = 0; a < 4; ++a) ranks.insert(owner[mesh.cell(e)[a]]);
      cut_cells += ranks.size() > 1;
    }
    EXPECT_LE(cut_cells, 2 * 32 * (parts - 1)) << parts << " parts";
    EXPECT_EQ(owner, partition_nodes({{&mesh, 0}}, mesh.node_count(), parts)) << "every rank computes the same";
  }
  const std::vector<int> alone = partition_nodes({{&mesh, 0}}, mesh.node_count(), 1);
  EXPECT_TRUE(std::all_of(alone.begin(), alone.end(), [](int o) { return o == 0; }));
}

// Rank 1 of two, with rank 0's rows supplied by a stand-in for MPI.
class TwoRankStandIn final : public petsc_plugin::Communicator {
 public:
  std::vector<double> rank0_values;
  int rank() const override { return 1; }
  int size() const override { return 2; }
  void all_gather(const double* mine, const int* counts, double* all) const override {
    std::copy(rank0_values.begin(), rank0_values.begin() + counts[0], all);
    std::copy(mine, mine + counts[1], all + counts[0]);
  }
};

TEST(RowOwnership, RowsFollowTheirNodesAndTheGatheredResidualLandsInPlace) {
  // Three nodes with two fields each; node 1's second dof is prescribed. Nodes 0 and 2 belong to
  // rank 0, node 1 to rank 1.
  const std::vector<int> node_owner = {0, 1, 0};
  const std::vector<Index> free_index = {0, 1, 2, -1, 3, 4};
  TwoRankStandIn world;
  const RowOwnership rows = own_rows_by_node(node_owner, free_index, 2, 5, world);
  EXPECT_EQ(rows.owner, (std::vector<int>{0, 0, 1, 0, 0}));
  EXPECT_EQ(rows.counts, (std::vector<int>{4, 1}));
  EXPECT_EQ(rows.by_rank, (std::vector<Index>{0, 1, 3, 4, 2}));
  EXPECT_TRUE(rows.owns(2));
  EXPECT_FALSE(rows.owns(0));
  // Rank 1 assembled its row (2) right and the others partly; rank 0 sends its rows 0, 1, 3, 4.
  world.rank0_values = {10, 11, 13, 14};
  VectorX residual(5);
  residual << -1, -1, 12, -1, -1;
  rows.complete(residual);
  EXPECT_EQ(residual, (VectorX(5) << 10, 11, 12, 13, 14).finished());
}

}  // namespace
}  // namespace moreau
