// A solid model divided among two ranks (threads standing in for MPI): each rank assembles only the
// cells that touch its nodes, yet after the gathers it holds the whole force, the energy and its own
// rows of the tangent with the same bits as one process. This is what lets `mpirun -np N` take the
// same Newton steps as one process (tests/fem/petsc/test_mpi_runs.cpp runs it end to end).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "fem_test_helpers.hpp"
#include "moreau/fem/solids/fem_assembly.hpp"
#include "moreau/fem/solids/solid_partition.hpp"
#include "thread_ranks.hpp"

namespace moreau {
namespace {

// Two solids of different element types (so the second's nodes and cells are offset): a hex8 bar
// clamped at its left end and a tet4 block beside it.
FemModel two_solids() {
  FemModel model;
  model.dim = 3;
  add_fem_solid(model, test::fem_solid("bar", make_box_mesh(Vec3(0, 0, 0), Vec3(1, 0.3, 0.3), {8, 3, 3}, ElementType::hex8),
                                       test::fem_material(HyperelasticModel::neo_hookean, 1e6, 0.3)));
  add_fem_solid(model, test::fem_solid("block", make_box_mesh(Vec3(0, 0.5, 0), Vec3(0.4, 0.9, 0.4), {3, 3, 3}, ElementType::tet4),
                                       test::fem_material(HyperelasticModel::st_venant_kirchhoff, 2e6, 0.25)));
  test::prescribe_nodes(model, test::boundary_global_nodes(model, 0, "left"), [](const Vec3&) { return Vec3::Zero(); });
  test::prescribe_nodes(model, test::boundary_global_nodes(model, 1, "bottom"), [](const Vec3&) { return Vec3::Zero(); });
  finalize_fem_model(model);
  return model;
}

// A smooth, large deformation (bending and twisting, a few per cent strain).
VectorX deformation(const FemModel& model, Real scale) {
  VectorX u(model.dof_count());
  for (Index n = 0; n < model.node_count; ++n) {
    const Vec3 X = model.reference_position(n);
    u.segment<3>(3 * n) = scale * Vec3(0.02 * std::sin(3 * X.y()), 0.1 * X.x() * X.x(), 0.05 * X.x() * X.y());
  }
  return u;
}

bool same_bits(const VectorX& a, const VectorX& b) { return a.size() == b.size() && (a.array() == b.array()).all(); }

// Entries of the rows of `rows` (free indices it owns) in a column-major pattern: (row, column, value).
std::vector<std::array<Real, 3>> entries_of_rows(const SparseMatrix& K, const RowOwnership* rows) {
  std::vector<std::array<Real, 3>> out;
  for (int c = 0; c < K.outerSize(); ++c)
    for (SparseMatrix::InnerIterator it(K, c); it; ++it)
      if (!rows || rows->owns(it.row())) out.push_back({Real(it.row()), Real(c), it.value()});
  return out;
}

struct RankResult {
  InternalForceResult state, step_state;
  VectorX force, step_force, product;
  std::vector<std::array<Real, 3>> tangent, step_tangent, whole_tangent_rows, whole_step_tangent_rows;
  Index assembled_cells = 0;
  std::vector<int> counts;
};

TEST(DistributedSolidAssembly, EachRankHoldsTheForcesEnergyAndItsTangentRowsOfOneProcess) {
  const FemModel whole = two_solids();
  const VectorX u = deformation(whole, 1), u_next = deformation(whole, 1.3), direction = deformation(whole, 0.7);
  VectorX force, step_force;
  SparseMatrix K, K_step;
  const InternalForceResult state = assemble_internal_forces(whole, u, force, &K, 1);
  const InternalForceResult step_state = assemble_step_forces(whole, u, u_next, StepRule::midpoint, step_force, &K_step, 1);
  const VectorX product = tangent_times(whole, u, direction);
  ASSERT_TRUE(state.valid && step_state.valid);

  std::array<RankResult, 2> ranks;
  test::ThreadRanks(2).run([&](const petsc_plugin::Communicator& world) {
    FemModel model = two_solids();
    distribute_fem_model(model, world);
    RankResult& r = ranks[world.rank()];
    SparseMatrix Kr, Kr_step;
    r.state = assemble_internal_forces(model, u, r.force, &Kr, 1);
    r.step_state = assemble_step_forces(model, u, u_next, StepRule::midpoint, r.step_force, &Kr_step, 1);
    r.product = tangent_times(model, u, direction);
    r.tangent = entries_of_rows(Kr, nullptr);
    r.step_tangent = entries_of_rows(Kr_step, nullptr);
    r.whole_tangent_rows = entries_of_rows(K, &model.partition->rows);
    r.whole_step_tangent_rows = entries_of_rows(K_step, &model.partition->rows);
    r.assembled_cells = model.partition->assembled_cells;
    r.counts = model.partition->rows.counts;
  });

  Index cells = 0;
  for (const FemSolid& s : whole.solids) cells += s.mesh.cell_count();
  for (int rank = 0; rank < 2; ++rank) {
    const RankResult& r = ranks[rank];
    EXPECT_TRUE(same_bits(r.force, force)) << "rank " << rank;
    EXPECT_TRUE(same_bits(r.step_force, step_force)) << "rank " << rank;
    EXPECT_TRUE(same_bits(r.product, product)) << "rank " << rank;
    EXPECT_EQ(r.state.energy, state.energy) << "rank " << rank;
    EXPECT_EQ(r.step_state.energy, step_state.energy) << "rank " << rank;
    // Its tangent holds exactly its own rows, entry for entry.
    EXPECT_EQ(r.tangent, r.whole_tangent_rows) << "rank " << rank;
    EXPECT_EQ(r.step_tangent, r.whole_step_tangent_rows) << "rank " << rank;
    EXPECT_LT(r.assembled_cells, cells) << "rank " << rank;
  }
  // Together they assemble every cell, those along the cut twice (METIS balances nodes, not cells:
  // the tet4 block has more cells per node than the hex8 bar).
  EXPECT_GE(ranks[0].assembled_cells + ranks[1].assembled_cells, cells);
  EXPECT_EQ(ranks[0].counts, ranks[1].counts);
  EXPECT_EQ(ranks[0].counts[0] + ranks[0].counts[1], whole.free_count);
  EXPECT_EQ(ranks[0].tangent.size() + ranks[1].tangent.size(), static_cast<size_t>(K.nonZeros()));
}

TEST(DistributedSolidAssembly, AnInvertedCellIsReportedByEveryRank) {
  // The bar's free end pushed back through itself inverts cells that only one rank assembles.
  const FemModel whole = two_solids();
  VectorX u = VectorX::Zero(whole.dof_count());
  for (Index n : test::boundary_global_nodes(whole, 0, "right")) u[whole.dof(n, 0)] = -0.3;
  VectorX force;
  const InternalForceResult state = assemble_internal_forces(whole, u, force, nullptr, 1);
  ASSERT_FALSE(state.valid);
  std::array<InternalForceResult, 2> ranks;
  std::array<bool, 2> assembles_it{false, false};
  test::ThreadRanks(2).run([&](const petsc_plugin::Communicator& world) {
    FemModel model = two_solids();
    distribute_fem_model(model, world);
    VectorX f;
    ranks[world.rank()] = assemble_internal_forces(model, u, f, nullptr, 1);
    for (const std::vector<Index>& colour : model.partition->colours[0])
      if (std::find(colour.begin(), colour.end(), state.invalid_cell) != colour.end()) assembles_it[world.rank()] = true;
  });
  // One rank alone computes the first inverted cell: the other knows of it from the gather.
  EXPECT_NE(assembles_it[0], assembles_it[1]);
  for (const InternalForceResult& r : ranks) {
    EXPECT_FALSE(r.valid);
    EXPECT_EQ(r.invalid_solid, state.invalid_solid);
    EXPECT_EQ(r.invalid_cell, state.invalid_cell);
  }
}

}  // namespace
}  // namespace moreau
