// Rigid bodies immersed in the FEM fluid (fem/immersed/immersed_rigid_body): a free ring between
// two cylinders against the torque balance, a free cylinder in simple shear, a neutrally buoyant
// disc under gravity, the energy law of a falling disc, the coupling's Jacobian against
// differences of its residual, and determinism across thread counts.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>

#include "flow_source_jacobian.hpp"
#include "flow_test_helpers.hpp"
#include "immersed_rigid_body_fixtures.hpp"
#include "immersed_test_meshes.hpp"
#include "moreau/fem/flow/flow_problem.hpp"
#include "moreau/fem/flow/flow_stepper.hpp"
#include "moreau/fem/immersed/immersed_coupling.hpp"

namespace moreau {
namespace {

using test::annulus_mesh;
using test::disc_mesh;
using test::fix_pressure;
using test::prescribe_velocity;

Real angular_velocity(const ImmersedSolidState& state) {
  return rigid_frame_angular_velocity(state.frame[0], state.frame_velocity[0], 2).z();
}

TEST(ImmersedRigidBody, AFreeRingBetweenTurningCylindersTurnsAtTheRateItsTorquesBalance) {
  // Circular Couette flow between a cylinder of radius r1 turning at Omega and a fixed wall at r2,
  // with a free rigid ring r3 <= r <= r4 in the gap. At steady (Stokes) state each gap carries
  // the Couette torque per unit length between its walls' rates, T = 4 pi mu dOmega a^2 b^2 /
  // (b^2 - a^2), and the ring carries no torque of its own, so
  //   (Omega - w) r1^2 r3^2 / (r3^2 - r1^2) = w r4^2 r2^2 / (r2^2 - r4^2).
  // The ring's faces lie on circles of fluid nodes (16 cells across the gap, r3 and r4 at the
  // 6th and 10th; see the elastic ring's test for why). The ring's mesh is twice as fine as the
  // fluid's around and across, so the fluid between its nodes is held. Errors: the polygonal
  // circles (1 - cos(pi/128), 3e-4), the Q1 fields across the gaps (the Couette profile A r + B/r
  // is not bilinear, O(h^2), about 1e-3) and the ring's slip (about 1e-3 h / width, 1e-4): the
  // tolerance is 0.5 %.
  const Real r1 = 0.5, r2 = 1.0, r3 = 0.6875, r4 = 0.8125, Omega = 0.1, dt = 0.05;
  const NavierStokesModel m = test::couette_gap_fluid(Omega);  // r1, r2 as above, mu = 1 Pa s
  const ImmersedSolids solids = test::one_rigid_body(annulus_mesh(r3, r4, 8, 256), 1, m, dt);
  ImmersedSolidState state = initial_immersed_state(solids);
  ImmersedCoupling coupling(m, solids, state);
  VectorX x = VectorX::Zero(m.dof_count());
  FlowStepper stepper(FlowIntegrator::backward_euler);
  FlowLinearSolver solver;
  Real w = 0, change = 1;
  int steps = 0;
  for (; steps < 200 && change > 1e-9; ++steps) {
    const FlowSolveResult r = stepper.step(m, dt * steps, dt, x, solver, {.tolerance = 1e-10, .max_iterations = 40}, &coupling);
    ASSERT_TRUE(r.converged) << r.failure;
    const Real now = angular_velocity(state);
    change = std::abs(now - w);
    w = now;
  }
  const Real a = r1 * r1 * r3 * r3 / (r3 * r3 - r1 * r1), c = r4 * r4 * r2 * r2 / (r2 * r2 - r4 * r4);
  const Real expected = Omega * a / (a + c);
  // The ring stays round and centred: its frame's directors orthonormal, its centre at the origin.
  const VectorX& q = state.frame[0];
  const Real drift = q.head(2).norm(), stretch = std::abs(q.segment(2, 2).norm() - 1);
  std::printf("free ring after %d steps: %.6e rad/s, expected %.6e rad/s (%+.3f %%); centre drift %.1e m, |d1| - 1 = %.1e\n",
              steps, w, expected, 100 * (w / expected - 1), drift, stretch);
  EXPECT_LT(change, 1e-9);
  EXPECT_NEAR(w / expected, 1, 0.005);
  EXPECT_LT(drift, 1e-9);
  EXPECT_LT(stretch, 1e-9);
}

TEST(ImmersedRigidBody, ANeutrallyBuoyantCylinderInSimpleShearTurnsAtHalfTheShearRate) {
  // A free cylinder (radius 0.25) at the centre of a square whose sides move with the simple shear
  // u = (gamma y, 0), at Reynolds number rho gamma R^2 / mu = 0.06: it turns at -gamma/2, the
  // rotation of the shear (Jeffery 1922; Einstein). The shear is a rotation -gamma/2 plus a strain
  // symmetric about the diagonal y = x, which turns a torque-free body that shares the symmetry
  // (both meshes do) neither way, so the walls' nearness does not change the rate and what is
  // left is inertia (O(Re^3/2)) and the time to steady state (steps up to 2 s, viscous time
  // rho L^2 / mu = 1 s). Tolerance: the 2 %. The quantitative test of the torque is the ring's.
  const Real gamma = 1, dt = 0.05;
  NavierStokesModel m;
  m.mesh = make_rectangle_mesh(Vec2(-1, -1), Vec2(1, 1), {48, 48}, ElementType::quad4);
  m.density = 1;
  m.viscosity = 1;
  for (const char* side : {"left", "right", "bottom", "top"})
    prescribe_velocity(m, side, [&](const Vec3& p) { return Vec3(gamma * p.y(), 0, 0); });
  fix_pressure(m, 0);
  setup_navier_stokes(m);
  const ImmersedSolids solids = test::one_rigid_body(disc_mesh(Vec3::Zero(), 0.25, 12, 4), 1, m, dt);
  ImmersedSolidState state = initial_immersed_state(solids);
  ImmersedCoupling coupling(m, solids, state);
  VectorX x = VectorX::Zero(m.dof_count());
  FlowStepper stepper(FlowIntegrator::midpoint);
  FlowLinearSolver solver;
  for (int step = 0; step < 40; ++step) {
    const FlowSolveResult r = stepper.step(m, dt * step, dt, x, solver, {.tolerance = 1e-10}, &coupling);
    ASSERT_TRUE(r.converged) << r.failure;
  }
  const Real w = angular_velocity(state);
  std::printf("cylinder in shear: %.6f rad/s, expected %.6f (%+.3f %%); centre at (%.1e, %.1e) m\n", w, -gamma / 2,
              100 * (w / (-gamma / 2) - 1), state.frame[0][0], state.frame[0][1]);
  EXPECT_NEAR(w / (-gamma / 2), 1, 0.02);
  EXPECT_LT(state.frame[0].head(2).norm(), 1e-6);
}

// A closed box [0, 1] x [0, 1.5] of fluid (rho 1, mu 0.01) under gravity with a disc of radius 0.1
// and density rho_s at (0.5, 1), released at rest.
struct DiscInABox {
  NavierStokesModel fluid;
  ImmersedSolids solids;
  ImmersedSolidState state;
};

DiscInABox disc_in_a_box(Real density, Real dt) {
  DiscInABox b;
  b.fluid = test::closed_box_fluid(true);
  b.solids = test::one_rigid_body(disc_mesh(Vec3(0.5, 1, 0), 0.1, 8, 3), density, b.fluid, dt);
  b.state = initial_immersed_state(b.solids);
  return b;
}

// Midpoint steps of 0.01 s of the disc's box from x (`after_each` runs after each); false, with the
// failure reported, if one does not converge.
bool fall(DiscInABox& b, VectorX& x, int steps, Real tolerance, const std::function<void()>& after_each = {}) {
  ImmersedCoupling coupling(b.fluid, b.solids, b.state);
  FlowStepper stepper(FlowIntegrator::midpoint);
  FlowLinearSolver solver;
  for (int step = 0; step < steps; ++step) {
    const FlowSolveResult r = stepper.step(b.fluid, 0.01 * step, 0.01, x, solver, {.tolerance = tolerance}, &coupling);
    if (!r.converged) {
      ADD_FAILURE() << "step " << step << ": " << r.failure;
      return false;
    }
    if (after_each) after_each();
  }
  return true;
}

// Fluid kinetic energy + the body's excess kinetic energy + the excess mass's potential energy.
Real total_energy(const DiscInABox& b, const VectorX& x) {
  const Real excess_mass = b.solids.rigid_bodies[0].excess_mass(0, 0);
  const Real height = b.state.frame[0][1];
  return flow_kinetic_energy(b.fluid, x) + immersed_excess_kinetic_energy(b.solids, b.fluid, b.state) +
         excess_mass * 9.81 * height;
}

TEST(ImmersedRigidBody, WithTheFluidsDensityNothingMoves) {
  // A disc of the fluid's density under gravity: the hydrostatic state is the solution (pressure
  // linear in depth, exact in Q1), so after ten steps the velocity is round-off (of a pressure of
  // 15 Pa over 0.04 m cells, divided by the step's mass: 1e-12 m/s) and the disc has not moved.
  DiscInABox b = disc_in_a_box(1, 0.01);
  VectorX x = VectorX::Zero(b.fluid.dof_count());
  ASSERT_TRUE(fall(b, x, 10, 1e-10));
  Real speed = 0;
  for (Index n = 0; n < b.fluid.mesh.node_count(); ++n)
    for (int k = 0; k < 2; ++k) speed = std::max(speed, std::abs(x[b.fluid.dof(n, k)]));
  const Real moved = (b.state.frame[0] - rigid_frame_at_rest(b.solids.rigid_bodies[0], 2)).lpNorm<Eigen::Infinity>();
  std::printf("neutrally buoyant disc: largest fluid speed %.2e m/s, frame moved by %.2e\n", speed, moved);
  EXPECT_LT(speed, 1e-9);
  EXPECT_LT(moved, 1e-11);
}

TEST(ImmersedRigidBody, AFallingDiscInAClosedBoxNeverGainsEnergy) {
  // A disc twice as dense as the fluid falls from rest. The fluid's kinetic energy, the disc's
  // excess kinetic energy and its excess weight's potential energy can only be dissipated: by the
  // fluid's viscosity and the coupling's slip (the midpoint rule makes the frame's constraint
  // forces workless and the coupling's power dt k W |slip|^2 >= 0). Per step the total may rise by
  // no more than the Newton tolerance allows (1e-12 of the residual: 1e-9 of the energy).
  DiscInABox b = disc_in_a_box(2, 0.01);
  VectorX x = VectorX::Zero(b.fluid.dof_count());
  const Real E0 = total_energy(b, x);
  Real previous = E0, largest_rise = -kInfinity;
  ASSERT_TRUE(fall(b, x, 30, 1e-12, [&] {
    const Real E = total_energy(b, x);
    largest_rise = std::max(largest_rise, E - previous);
    previous = E;
  }));
  const Real fall = 1 - b.state.frame[0][1], speed = -b.state.frame_velocity[0][1];
  std::printf("falling disc: fell %.4f m, speed %.4f m/s; energy %.6e -> %.6e J/m, largest rise in a step %.2e J/m\n",
              fall, speed, E0, previous, largest_rise);
  EXPECT_GT(fall, 0.05);  // it did fall: free fall with the added mass of a disc, (rho_s - rho_f)/(rho_s + rho_f) g t^2/2, is 0.15 m
  EXPECT_LT(previous, E0);
  EXPECT_LE(largest_rise, 1e-9 * E0);
}

// The falling disc's box with a disc three times denser than the fluid, its frame already moving
// and turned by 0.3 rad, ready for a step of 0.01 s.
DiscInABox moving_turned_disc() {
  DiscInABox b = disc_in_a_box(3, 0.01);
  const Real turn = 0.3;
  VectorX& q = b.state.frame[0];
  q.segment(2, 2) = Vec2(std::cos(turn), std::sin(turn));
  q.segment(4, 2) = Vec2(-std::sin(turn), std::cos(turn));
  b.state.frame_velocity[0] << 0.1, -0.2, -0.5 * std::sin(turn), 0.5 * std::cos(turn), -0.5 * std::cos(turn),
      -0.5 * std::sin(turn);
  return b;
}

TEST(ImmersedRigidBody, TheSourcesJacobianIsTheDerivativeOfItsResidual) {
  // The moving, turned disc in a swirling fluid velocity, one step of the midpoint rule and one of
  // backward Euler (which also starts the midpoint rule): every column of the source's Jacobian
  // that the body touches matches central differences of its residual. The columns include the
  // frame's response (the implicit function's derivative) and the points' motion inside the
  // fluid's cells. The penalty forces k W slip (k = 1e5 Pa s/m^2) carry the frame's round-off,
  // which central differences divide by h: in the columns of fluid dofs at the body's edge, which
  // the body barely touches, that swamps the column (per column, the difference fell as 1/h:
  // 8.6e-5 at h = 1e-7, 1.2e-5 at 1e-6, 7.8e-7 at 1e-5, 1.4e-7 at 1e-4, in 3D 9.5e-5, 1.1e-5 and
  // 1.0e-6 at 1e-5, 1e-4 and 1e-3: the quotient's error, not the Jacobian's). So the differences
  // are measured against the largest column, with h = 1e-4 m/s (the residual is nearly linear:
  // truncation is below 1e-8; measured 1.1e-10 (midpoint) and 3.8e-11 (backward Euler) in 2D,
  // 1.6e-10 in 3D).
  for (FlowIntegrator scheme : {FlowIntegrator::midpoint, FlowIntegrator::backward_euler}) {
    DiscInABox b = moving_turned_disc();
    ImmersedCoupling coupling(b.fluid, b.solids, b.state);
    const NavierStokesModel& m = b.fluid;
    VectorX x, x_n;
    test::swirling_velocities_2d(m, x, x_n);
    const FlowTimeStep step{scheme, 0.01, &x_n, &x_n};
    const auto [worst, columns] = test::source_jacobian_against_differences(coupling, m, x, step, 1e-4, true);
    std::printf("rigid body source Jacobian (%s): %d columns, largest difference from central differences %.2e of the "
                "largest column\n",
                scheme == FlowIntegrator::midpoint ? "midpoint" : "backward Euler", columns, worst);
    EXPECT_GT(columns, 50);
    EXPECT_LT(worst, 1e-8);
  }
}

TEST(ImmersedRigidBody, ItsLowRankJacobianIsTheDenseOne) {
  // What the flow's linear solve receives (sparse entries plus U V^T, applied by Woodbury) is the
  // same matrix as the dense Jacobian the differences check, to round-off.
  DiscInABox b = moving_turned_disc();
  ImmersedCoupling coupling(b.fluid, b.solids, b.state);
  const NavierStokesModel& m = b.fluid;
  VectorX x, x_n;
  test::swirling_velocities_2d(m, x, x_n);
  const FlowTimeStep step{FlowIntegrator::midpoint, 0.01, &x_n, &x_n};
  auto jacobian = [&](FlowLowRank* low_rank) {
    VectorX R = VectorX::Zero(m.dof_count());
    std::vector<Eigen::Triplet<Real, int>> entries;
    coupling.add(x, step, R, &entries, low_rank);
    SparseMatrix J(m.free_count, m.free_count);
    J.setFromTriplets(entries.begin(), entries.end());
    return Eigen::MatrixXd(J);
  };
  FlowLowRank low_rank;
  const Eigen::MatrixXd dense = jacobian(nullptr), split = jacobian(&low_rank);
  ASSERT_EQ(low_rank.U.cols(), 6);
  const Real difference = (split + low_rank.U * low_rank.V.transpose() - dense).norm() / dense.norm();
  const Real low_rank_share = (low_rank.U * low_rank.V.transpose()).norm() / dense.norm();
  std::printf("low-rank Jacobian: rank %d, %.2f of the dense Jacobian's norm, sparse + U V^T differs by %.1e\n",
              static_cast<int>(low_rank.U.cols()), low_rank_share, difference);
  EXPECT_GT(low_rank_share, 1e-3);  // the frame's response matters
  EXPECT_LT(difference, 1e-13);
}

TEST(ImmersedRigidBody, TheSourcesJacobianIsTheDerivativeOfItsResidualIn3D) {
  // As in 2D (and measured the same way), for a cube of 6^3 hex8 cells, three times denser than
  // the fluid, in an 8^3 box of fluid: a frame of twelve numbers with six internal constraints,
  // turned about an oblique axis and moving.
  NavierStokesModel m;
  m.mesh = make_box_mesh(Vec3(0, 0, 0), Vec3(1, 1, 1), {8, 8, 8}, ElementType::hex8);
  m.density = 1;
  m.viscosity = 0.01;
  for (const char* side : {"left", "right", "bottom", "top", "front", "back"})
    prescribe_velocity(m, side, [](const Vec3&) { return Vec3::Zero(); });
  fix_pressure(m, 0);
  setup_navier_stokes(m);
  const Real dt = 0.01;
  ImmersedSolids solids = test::one_rigid_body(make_box_mesh(Vec3(0.35, 0.35, 0.35), Vec3(0.65, 0.65, 0.65), {6, 6, 6},
                                                   ElementType::hex8), 3, m, dt);
  ImmersedSolidState state = initial_immersed_state(solids);
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(0.3, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  const Vec3 w(0.2, -0.4, 0.5), v(0.1, -0.2, 0.05);
  for (int i = 0; i < 3; ++i) {
    state.frame[0].segment(3 * (i + 1), 3) = turn.col(i);
    state.frame_velocity[0].segment(3 * (i + 1), 3) = w.cross(Vec3(turn.col(i)));
  }
  state.frame_velocity[0].head(3) = v;
  ImmersedCoupling coupling(m, solids, state);
  VectorX x = VectorX::Zero(m.dof_count()), x_n = VectorX::Zero(m.dof_count());
  for (Index n = 0; n < m.mesh.node_count(); ++n) {
    const Vec3& p = m.mesh.nodes[n];
    x[m.dof(n, 0)] = std::sin(3 * p.x() + 1) * std::cos(2 * p.y()) * p.z();
    x[m.dof(n, 1)] = 0.7 * std::cos(4 * p.x()) * std::sin(3 * p.y() + 0.5);
    x[m.dof(n, 2)] = 0.5 * std::sin(2 * p.z() + p.x());
    x_n[m.dof(n, 0)] = 0.5 * std::cos(2 * p.y() + 0.3);
    x_n[m.dof(n, 1)] = 0.4 * std::sin(3 * p.x());
    x_n[m.dof(n, 2)] = 0.3 * std::cos(p.y());
  }
  const FlowTimeStep step{FlowIntegrator::midpoint, dt, &x_n, &x_n};
  const auto [worst, columns] = test::source_jacobian_against_differences(coupling, m, x, step, 1e-4, true);
  std::printf("3D rigid body source Jacobian: %d columns, largest difference from central differences %.2e of the largest column\n",
              columns, worst);
  EXPECT_GT(columns, 100);
  EXPECT_LT(worst, 1e-8);
}

TEST(ImmersedRigidBody, StepsAreBitIdenticalForAnyThreadCount) {
  VectorX results[2], frames[2];
  for (int threads : {1, 2}) {
    DiscInABox b = disc_in_a_box(2, 0.01);
    ImmersedCoupling coupling(b.fluid, b.solids, b.state);
    VectorX x = VectorX::Zero(b.fluid.dof_count());
    FlowStepper stepper(FlowIntegrator::midpoint);
    FlowLinearSolver solver;
    for (int step = 0; step < 5; ++step)
      ASSERT_TRUE(stepper.step(b.fluid, 0.01 * step, 0.01, x, solver, {.threads = threads}, &coupling).converged);
    results[threads - 1] = x;
    frames[threads - 1] = b.state.frame[0];
  }
  EXPECT_EQ(0, std::memcmp(results[0].data(), results[1].data(), sizeof(Real) * results[0].size()));
  EXPECT_EQ(0, std::memcmp(frames[0].data(), frames[1].data(), sizeof(Real) * frames[0].size()));
}

}  // namespace
}  // namespace moreau
