// Immersed solids in the FEM fluid (fem/immersed): the locator that maps solid nodes into the
// fluid's cells, a solid at rest in a resting fluid, an elastic layer sheared by a Couette flow
// against its closed-form displacement, the energy balance of a released solid in a closed box,
// the coupling's Jacobian against differences of its residual, and determinism across thread counts.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>

#include "flow_source_jacobian.hpp"
#include "flow_test_helpers.hpp"
#include "immersed_rigid_body_fixtures.hpp"
#include "immersed_released_block.hpp"
#include "immersed_test_meshes.hpp"
#include "moreau/fem/core/mesh_locator.hpp"
#include "moreau/fem/flow/flow_problem.hpp"
#include "moreau/fem/flow/flow_stepper.hpp"
#include "moreau/fem/immersed/immersed_coupling.hpp"

namespace moreau {
namespace {

using test::annulus_mesh;
using test::fix_pressure;
using test::prescribe_velocity;
using test::rectangle_solid;
using test::released_block;
using test::ReleasedBlock;
using test::total_energy;

TEST(MeshLocator, FindsTheCellAndReferenceCoordinatesOfPointsInADistortedMesh) {
  // A 2D mesh with its interior nodes displaced (cells stay convex) and a 3D box: every random
  // point is found in a cell whose isoparametric map sends the returned xi back to the point, and
  // points outside are not found.
  for (int dim : {2, 3}) {
    FemMesh mesh = dim == 2 ? make_rectangle_mesh(Vec2(0, 0), Vec2(2, 1), {12, 7}, ElementType::quad4)
                            : make_box_mesh(Vec3(0, 0, 0), Vec3(1, 2, 1), {5, 7, 4}, ElementType::hex8);
    std::mt19937 random(7);
    std::uniform_real_distribution<Real> unit(0, 1);
    if (dim == 2)
      for (Vec3& p : mesh.nodes)
        if (p.x() > 0 && p.x() < 2 && p.y() > 0 && p.y() < 1) p += 0.03 * Vec3(unit(random) - 0.5, unit(random) - 0.5, 0);
    const MeshLocator locator(mesh);
    const Vec3 extent = dim == 2 ? Vec3(2, 1, 0) : Vec3(1, 2, 1);
    for (int i = 0; i < 500; ++i) {
      const Vec3 point = extent.cwiseProduct(Vec3(unit(random), unit(random), unit(random)));
      const std::optional<MeshPoint> at = locator.locate(point);
      ASSERT_TRUE(at) << "point " << point.transpose();
      Vec3 mapped = Vec3::Zero();
      Real sum = 0;
      for (int a = 0; a < mesh.nodes_per_cell(); ++a) {
        mapped += at->shape[a] * mesh.nodes[mesh.cell(at->cell)[a]];
        sum += at->shape[a];
        EXPECT_GE(at->shape[a], -1e-9);
      }
      EXPECT_LT((mapped - point).norm(), 1e-12);
      EXPECT_NEAR(sum, 1, 1e-14);
    }
    EXPECT_FALSE(locator.locate(Vec3(-0.01, 0.5, 0.5)));
    EXPECT_FALSE(locator.locate(extent + Vec3(0.01, 0.01, dim == 3 ? 0.01 : 0)));
  }
}

// The fluid's velocity components, as a vector over nodes.
Real largest_speed(const NavierStokesModel& m, const VectorX& x) {
  Real v = 0;
  for (Index n = 0; n < m.mesh.node_count(); ++n)
    for (int k = 0; k < m.dim(); ++k) v = std::max(v, std::abs(x[m.dof(n, k)]));
  return v;
}

TEST(ImmersedSolid, WithTheFluidsDensityAndNoLoadNothingMoves) {
  // A closed box of water under gravity with a block of the same density inside: the discrete
  // hydrostatic state (pressure linear in depth, exact in Q1) is the solution, so after ten
  // midpoint steps the velocity is round-off and the block has not moved.
  NavierStokesModel m;
  m.mesh = make_rectangle_mesh(Vec2(0, 0), Vec2(1, 1), {16, 16}, ElementType::quad4);
  m.density = 1000;
  m.viscosity = 1e-3;
  m.body_force = Vec3(0, -9.81, 0);
  for (const char* side : {"left", "right", "bottom", "top"}) prescribe_velocity(m, side, [](const Vec3&) { return Vec3::Zero(); });
  fix_pressure(m, 0);
  setup_navier_stokes(m);
  const ImmersedSolids solids = rectangle_solid(Vec2(0.3, 0.4), Vec2(0.7, 0.6), {16, 8}, 1e4, 1000, 1e-3);
  ImmersedSolidState state = initial_immersed_state(solids);
  ImmersedCoupling coupling(m, solids, state);
  VectorX x = VectorX::Zero(m.dof_count());
  FlowStepper stepper(FlowIntegrator::midpoint);
  FlowLinearSolver solver;
  for (int step = 0; step < 10; ++step) {
    const FlowSolveResult r = stepper.step(m, 0.01 * step, 0.01, x, solver, {.tolerance = 1e-10}, &coupling);
    ASSERT_TRUE(r.converged) << r.failure;
  }
  std::printf("resting block: largest fluid speed %.2e m/s, largest solid displacement %.2e m\n", largest_speed(m, x),
              state.displacement.lpNorm<Eigen::Infinity>());
  // Round-off of a pressure of 1e4 Pa over 1e-2 m cells, divided by the step's mass: 1e-9 m/s.
  EXPECT_LT(largest_speed(m, x), 1e-9);
  EXPECT_LT(state.displacement.lpNorm<Eigen::Infinity>(), 1e-11);
  EXPECT_NEAR(state.time, 0.1, 1e-14);
}

TEST(ImmersedSolid, AnElasticRingShearedByACouetteFlowTurnsAsTheClosedFormSays) {
  // Circular Couette flow between a cylinder of radius r1 turning at Omega and a ring of
  // Neo-Hookean solid (shear modulus G) lining the fixed outer wall, r3 <= r <= r2. At steady state
  // the ring is at rest and the fluid carries the torque per unit length
  //   T = 4 pi mu Omega r1^2 r3^2 / (r3^2 - r1^2)
  // into it; in the ring the shear stress T / (2 pi r^2) is G gamma exactly (a Neo-Hookean solid
  // in azimuthal shear), gamma = r dphi/dr, so its inner face has turned by
  //   phi(r3) = T / (4 pi G) (1/r3^2 - 1/r2^2).
  // No ends: the geometry is closed. The ring's inner face lies on a line of fluid nodes (16 cells
  // across the fluid's gap r1 <= r <= r2, r3 at the tenth): a face inside a fluid cell is felt at
  // the cell's inner edge, since the fluid's bilinear velocity vanishes at the solid's nodes in the
  // cell and so over all of it (with r3 = 0.8 mid-cell the face turned 17 % too far and the torque
  // was that of a gap one cell narrower, +3.2 %). Errors: the polygonal circles (1 - cos(pi/n),
  // 3e-4 at 128 cells around) and the Q1 fields across the gap (the Couette profile A r + B/r is
  // not bilinear), O(h^2), each of order 1e-3: the tolerance is 0.5 % (measured 0.06 %).
  const Real r1 = 0.5, r3 = 0.8125, r2 = 1.0, Omega = 0.1, mu = 1, G = 10, pi = std::acos(-1.0);
  NavierStokesModel m;
  m.mesh = annulus_mesh(r1, r2, 16, 128);
  m.density = 1;
  m.viscosity = mu;
  prescribe_velocity(m, "inner", [&](const Vec3& p) { return Vec3(-Omega * p.y(), Omega * p.x(), 0); });
  prescribe_velocity(m, "outer", [](const Vec3&) { return Vec3::Zero(); });
  fix_pressure(m, 0);
  setup_navier_stokes(m);
  ImmersedSolids solids;
  solids.model.dim = 2;
  FemSolid ring;
  ring.name = "ring";
  ring.mesh = annulus_mesh(r3, r2, 12, 128);
  ring.material.lame = lame_from_youngs(2 * G * 1.3, 0.3);
  ring.material.density = 1;
  add_fem_solid(solids.model, std::move(ring));
  for (Index n : solids.model.solids[0].mesh.boundary_nodes("outer"))
    for (int k = 0; k < 2; ++k) solids.model.prescribed.push_back({solids.model.dof(n, k), [](Real) { return 0.0; }});
  finalize_fem_model(solids.model);
  solids.viscosity.push_back(mu);
  ImmersedSolidState state = initial_immersed_state(solids);
  ImmersedCoupling coupling(m, solids, state);
  VectorX x = VectorX::Zero(m.dof_count());
  FlowStepper stepper(FlowIntegrator::backward_euler);
  FlowLinearSolver solver;
  const FemMesh& mesh = solids.model.solids[0].mesh;
  // The mean angle the ring's inner face has turned through.
  auto inner_turn = [&] {
    Real sum = 0;
    const std::vector<Index> inner = mesh.boundary_nodes("inner");
    for (Index n : inner) {
      const Vec3 X = mesh.nodes[n], x_now = X + Vec3(state.displacement[2 * n], state.displacement[2 * n + 1], 0);
      sum += std::atan2(X.x() * x_now.y() - X.y() * x_now.x(), X.dot(x_now));
    }
    return sum / inner.size();
  };
  const Real dt = 0.05;
  Real turn = 0, change = 1;
  int steps = 0;
  for (; steps < 200 && change > 1e-9; ++steps) {
    const FlowSolveResult r = stepper.step(m, dt * steps, dt, x, solver, {.tolerance = 1e-9, .max_iterations = 40}, &coupling);
    ASSERT_TRUE(r.converged) << r.failure;
    const Real now = inner_turn();
    change = std::abs(now - turn);
    turn = now;
  }
  const Real T = 4 * pi * mu * Omega * r1 * r1 * r3 * r3 / (r3 * r3 - r1 * r1);
  const Real expected = T / (4 * pi * G) * (1 / (r3 * r3) - 1 / (r2 * r2));
  std::printf("sheared ring after %d steps: inner face turned %.6e rad, expected %.6e rad (%+.3f %%)\n", steps, turn,
              expected, 100 * (turn / expected - 1));
  EXPECT_LT(change, 1e-9);
  EXPECT_NEAR(turn / expected, 1, 0.005);
}

TEST(ImmersedSolid, AReleasedBlockInAClosedBoxNeverGainsEnergy) {
  // No inflow and no load: the fluid's kinetic energy plus the block's elastic energy can only be
  // dissipated by viscosity. The midpoint rule with the block's discrete-gradient force makes the
  // block's elastic power exactly the work the fluid does on it, so the total falls step by step
  // (to the Newton tolerance, 1e-10 of the residual) whether the block keeps the fluid's
  // viscosity (Kelvin-Voigt, the default) or has none of its own (the seed's formula).
  for (Real solid_viscosity : {0.01, 0.0}) {
    ReleasedBlock b = released_block(solid_viscosity);
    ImmersedCoupling coupling(b.fluid, b.solids, b.state);
    VectorX x = VectorX::Zero(b.fluid.dof_count());
    FlowStepper stepper(FlowIntegrator::midpoint);
    FlowLinearSolver solver;
    const Real E0 = total_energy(b, x);
    Real previous = E0, largest_rise = 0, kinetic_peak = 0;
    for (int step = 0; step < 40; ++step) {
      const FlowSolveResult r = stepper.step(b.fluid, 0.01 * step, 0.01, x, solver, {.tolerance = 1e-12}, &coupling);
      ASSERT_TRUE(r.converged) << r.failure;
      const Real E = total_energy(b, x);
      largest_rise = std::max(largest_rise, E - previous);
      kinetic_peak = std::max(kinetic_peak, flow_kinetic_energy(b.fluid, x));
      previous = E;
    }
    std::printf("released block, solid viscosity %g Pa s: energy %.6e -> %.6e J/m, peak fluid kinetic %.3e J/m, largest "
                "rise in a step %.2e J/m\n",
                solid_viscosity, E0, previous, kinetic_peak, largest_rise);
    EXPECT_GT(kinetic_peak, 0.05 * E0);  // the block did set the fluid in motion
    EXPECT_LT(previous, 0.9 * E0);
    EXPECT_LE(largest_rise, 1e-9 * E0);
  }
}

TEST(ImmersedSolid, TheLoadOnAFreeSolidIsItsMassTimesAccelerationLessGravity) {
  // The fluid's load on a deformable solid is its nodal forces (what it applies to the fluid) plus
  // the inertia and weight of the fluid it displaces. With no clamp, the elastic and viscous
  // forces have no resultant, so the load must be Newton's law for the solid,
  // sum_C,D M^s_CD ((V_D,n+1 - V_D,n) / dt - g), whatever the deformation. A soft block three times
  // denser than the fluid falls from rest in a closed box for 20 midpoint steps of 0.01 s; it
  // deforms as it goes. Tolerance 1e-9 of the load: round-off in sums of forces of size 1 N/m.
  const NavierStokesModel m = test::closed_box_fluid(true);
  const ImmersedSolids solids = rectangle_solid(Vec2(0.4, 0.9), Vec2(0.6, 1.1), {8, 8}, 100, 3, 0.01);
  ImmersedSolidState state = initial_immersed_state(solids);
  ImmersedCoupling coupling(m, solids, state);
  VectorX x = VectorX::Zero(m.dof_count());
  FlowStepper stepper(FlowIntegrator::midpoint);
  FlowLinearSolver solver;
  const FemSolid& block = solids.model.solids[0];
  const int nodes = block.mesh.nodes_per_cell(), steps = 20;
  const Real dt = 0.01;
  Real worst = 0, weight = 0;
  for (Index e = 0; e < block.mesh.cell_count(); ++e)
    for (int k = 0; k < nodes * nodes; ++k) weight += 9.81 * block.cell_mass[static_cast<size_t>(e) * nodes * nodes + k];
  for (int step = 0; step < steps; ++step) {
    const VectorX before = state.velocity;
    const FlowSolveResult r = stepper.step(m, dt * step, dt, x, solver, {.tolerance = 1e-12}, &coupling);
    ASSERT_TRUE(r.converged) << r.failure;
    if (step == 0) continue;  // the midpoint rule starts with two half steps: the load is the second's
    Vec3 newton = Vec3::Zero();
    for (Index e = 0; e < block.mesh.cell_count(); ++e) {
      const Index* cell = block.mesh.cell(e);
      for (int a = 0; a < nodes; ++a)
        for (int c = 0; c < nodes; ++c)
          for (int i = 0; i < 2; ++i) {
            const Index d = solids.model.dof(block.node_begin + cell[c], i);
            newton[i] += block.cell_mass[static_cast<size_t>(e) * nodes * nodes + a * nodes + c] *
                         ((state.velocity[d] - before[d]) / dt - m.body_force[i]);
          }
    }
    worst = std::max(worst, (state.fluid_force[0] - newton).norm() / newton.norm());
  }
  std::printf("free block's load: %.6f N/m upwards against its weight %.6f N/m; largest difference from Newton's law %.1e; "
              "largest displacement %.3e m\n",
              state.fluid_force[0].y(), weight, worst, state.displacement.lpNorm<Eigen::Infinity>());
  EXPECT_LT(worst, 1e-9);
  EXPECT_GT(state.fluid_force[0].y(), 0);          // drag and buoyancy hold it up
  EXPECT_LT(state.fluid_force[0].y(), weight);     // but less than its weight: it falls faster and faster
  EXPECT_GT(state.displacement.lpNorm<Eigen::Infinity>(), 1e-3);
}

TEST(ImmersedSolid, TheSourcesJacobianIsTheDerivativeOfItsResidual) {
  // The stretched block of released_block, 3x denser than the fluid (so the inertia term counts),
  // in a swirling fluid velocity, one midpoint step of 0.01 s: every column of the source's
  // Jacobian that the solid touches matches central differences of its residual. The columns
  // include the nodes' motion inside the fluid's cells (the mapping's and the spreading's
  // derivatives, about 20 % of the entries here); the solid keeps the fluid's viscosity, so the
  // one lagged term (the viscous difference's F) is absent. Central differences with h = 1e-6 of
  // velocities of order 1 m/s are exact to about 1e-8 of the column.
  ReleasedBlock b = released_block(0.01);
  b.solids = rectangle_solid(Vec2(0.3, 0.4), Vec2(0.7, 0.6), {16, 8}, 10, 3, 0.01);  // same mesh, denser
  ImmersedCoupling coupling(b.fluid, b.solids, b.state);
  const NavierStokesModel& m = b.fluid;
  VectorX x, x_n;
  test::swirling_velocities_2d(m, x, x_n);
  const FlowTimeStep step{FlowIntegrator::midpoint, 0.01, &x_n, &x_n};
  const auto [worst, columns] = test::source_jacobian_against_differences(coupling, m, x, step, 1e-6);
  std::printf("immersed source Jacobian: %d columns, largest relative difference from central differences %.2e\n",
              columns, worst);
  EXPECT_GT(columns, 100);
  EXPECT_LT(worst, 1e-6);
}

TEST(ImmersedSolid, TheWholeFlowJacobianWithTheSolidIsTheDerivativeOfTheResidual) {
  // As the source's test, for the whole flow (flow_source_assembly): the cells' terms, with the
  // solid's force density in the stabilization's residual, and the solid's. tau and nu_LSIC are
  // held fixed, as the assembly's Jacobian treats them; the columns are the velocities of the
  // fluid nodes within 0.3 m of the block's centre, measured against the largest column (h = 1e-6).
  ReleasedBlock b = released_block(0.01);
  b.solids = rectangle_solid(Vec2(0.3, 0.4), Vec2(0.7, 0.6), {16, 8}, 10, 3, 0.01);
  b.fluid.fixed_tau = 2e-3;
  b.fluid.fixed_lsic = 1e-3;
  ImmersedCoupling coupling(b.fluid, b.solids, b.state);
  VectorX x, x_n;
  test::swirling_velocities_2d(b.fluid, x, x_n);
  const FlowTimeStep step{FlowIntegrator::midpoint, 0.01, &x_n, &x_n};
  const auto [worst, columns] =
      test::flow_with_source_jacobian_against_differences(b.fluid, coupling, x, step, 1e-6, Vec3(0.5, 0.5, 0), 0.3);
  std::printf("flow with an immersed solid: %d columns, largest difference from central differences %.2e of the largest column\n",
              columns, worst);
  EXPECT_GT(columns, 200);
  EXPECT_LT(worst, 1e-7);
}

TEST(ImmersedSolid, StepsAreBitIdenticalForAnyThreadCount) {
  VectorX results[2], displacements[2];
  for (int threads : {1, 2}) {
    ReleasedBlock b = released_block(0.01);
    ImmersedCoupling coupling(b.fluid, b.solids, b.state);
    VectorX x = VectorX::Zero(b.fluid.dof_count());
    FlowStepper stepper(FlowIntegrator::midpoint);
    FlowLinearSolver solver;
    for (int step = 0; step < 5; ++step)
      ASSERT_TRUE(stepper.step(b.fluid, 0.01 * step, 0.01, x, solver, {.threads = threads}, &coupling).converged);
    results[threads - 1] = x;
    displacements[threads - 1] = b.state.displacement;
  }
  EXPECT_EQ(0, std::memcmp(results[0].data(), results[1].data(), sizeof(Real) * results[0].size()));
  EXPECT_EQ(0, std::memcmp(displacements[0].data(), displacements[1].data(), sizeof(Real) * displacements[0].size()));
}

}  // namespace
}  // namespace moreau
