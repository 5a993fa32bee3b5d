// Driven rigid bodies in the FEM fluid and the fluid's load on immersed bodies
// (fem/immersed/immersed_rigid_body, prescribed_rigid_motion): the frame of a prescribed motion,
// the torque on a ring turning between two fixed cylinders against circular Couette flow, the
// driven body's Jacobian against differences of its residual, and the load on a free body
// against Newton's law.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "flow_source_jacobian.hpp"
#include "flow_test_helpers.hpp"
#include "immersed_rigid_body_fixtures.hpp"
#include "immersed_test_meshes.hpp"
#include "moreau/fem/flow/flow_stepper.hpp"
#include "moreau/fem/immersed/immersed_coupling.hpp"
#include "moreau/fem/immersed/prescribed_rigid_motion.hpp"

namespace moreau {
namespace {

using test::annulus_mesh;
using test::disc_mesh;
using test::fix_pressure;
using test::prescribe_velocity;

TEST(PrescribedRigidMotion, TurnsExactlyAndMovesToSecondOrder) {
  // A 3D frame turning at a constant rate about an oblique axis: each step's rotation is exact, so
  // after 100 steps the directors are the rotation by w t to round-off. Its centre moves with
  // v = (cos t, 0, 0): the midpoint quadrature of v is second-order, its error after t = 1
  // sin(1) - sum dt cos(t_mid) ~ dt^2 sin(1) / 24, so halving dt divides it by 4.
  const Vec3 w = 0.8 * Vec3(1, 2, 2) / 3;
  const PrescribedRigidMotion motion{[](Real t) { return Vec3(std::cos(t), 0, 0); }, [w](Real) { return w; }};
  auto run = [&](int steps) {
    VectorX q = VectorX::Zero(12);
    for (int i = 0; i < 3; ++i) q[3 * (i + 1) + i] = 1;
    const Real dt = 1.0 / steps;
    for (int n = 0; n < steps; ++n) q = advance_prescribed_frame(motion, q, n * dt, dt, 3);
    return q;
  };
  const VectorX coarse = run(50), fine = run(100);
  const Mat3 exact = Eigen::AngleAxis<Real>(w.norm(), w.normalized()).toRotationMatrix();
  Real director_error = 0;
  for (int i = 0; i < 3; ++i) director_error = std::max(director_error, (fine.segment(3 * (i + 1), 3) - exact.col(i)).norm());
  const Real coarse_error = std::abs(coarse[0] - std::sin(1.0)), fine_error = std::abs(fine[0] - std::sin(1.0));
  std::printf("prescribed motion: directors off the exact rotation by %.1e; centre error %.3e (dt 0.02), %.3e (dt 0.01), "
              "ratio %.3f\n",
              director_error, coarse_error, fine_error, coarse_error / fine_error);
  EXPECT_LT(director_error, 1e-14);
  EXPECT_NEAR(coarse_error / fine_error, 4, 0.01);
  EXPECT_NEAR(fine_error, 1e-4 * std::sin(1.0) / 24, 1e-8);
  // The frame's velocity: dd_i/dt = w x d_i.
  const VectorX dq = prescribed_frame_velocity(motion, fine, 1, 3);
  EXPECT_NEAR(dq[0], std::cos(1.0), 1e-15);
  EXPECT_LT((dq.segment(3, 3) - w.cross(Vec3(fine.segment(3, 3)))).norm(), 1e-15);
}

TEST(ImmersedDrivenBody, ARingTurningBetweenFixedCylindersFeelsTheCouetteTorques) {
  // A rigid ring r3 <= r <= r4 driven at Omega between two fixed cylinders r1 and r2. At steady
  // (Stokes) state each gap is circular Couette flow, whose torque per unit length on its faster
  // wall is T = -4 pi mu Omega a^2 b^2 / (b^2 - a^2) (a, b its radii), so the fluid's torque on
  // the ring is
  //   T = -4 pi mu Omega (r1^2 r3^2 / (r3^2 - r1^2) + r4^2 r2^2 / (r2^2 - r4^2)).
  // The geometry is the free ring's test's (the ring's faces on circles of fluid nodes, its mesh
  // twice as fine as the fluid's), with the same error budget: polygonal circles 3e-4, the Q1
  // fields across the gaps about 1e-3, slip 1e-4. Tolerance 0.5 %. Its centre stays put: the
  // force is zero to round-off of the torque's size.
  const Real r1 = 0.5, r2 = 1.0, r3 = 0.6875, r4 = 0.8125, Omega = 0.1, mu = 1, dt = 0.05;
  const NavierStokesModel m = test::couette_gap_fluid(0);  // r1, r2 and mu as above, both walls fixed
  const PrescribedRigidMotion turning{[](Real) { return Vec3::Zero(); }, [&](Real) { return Vec3(0, 0, Omega); }};
  const ImmersedSolids solids = test::one_rigid_body(annulus_mesh(r3, r4, 8, 256), m.density, m, dt, turning);
  ImmersedSolidState state = initial_immersed_state(solids);
  ImmersedCoupling coupling(m, solids, state);
  VectorX x = VectorX::Zero(m.dof_count());
  FlowStepper stepper(FlowIntegrator::backward_euler);
  FlowLinearSolver solver;
  // The fluid reaches steady state within 1 s (the viscous time rho (r2 - r1)^2 / mu is 0.25 s);
  // after that the torque still wavers as the ring's nodes pass through the fluid's cells (a cell
  // every 10 steps): its mean over the last second is compared, its spread reported.
  Real smallest = kInfinity, largest = -kInfinity, sum = 0;
  const int steps = 40, averaged = 20;
  for (int step = 0; step < steps; ++step) {
    const FlowSolveResult r = stepper.step(m, dt * step, dt, x, solver, {.tolerance = 1e-10, .max_iterations = 40}, &coupling);
    ASSERT_TRUE(r.converged) << r.failure;
    if (step < steps - averaged) continue;
    const Real torque = state.fluid_torque[0].z();
    smallest = std::min(smallest, torque);
    largest = std::max(largest, torque);
    sum += torque;
  }
  const Real torque = sum / averaged;
  const Real expected =
      -4 * kPi * mu * Omega * (r1 * r1 * r3 * r3 / (r3 * r3 - r1 * r1) + r4 * r4 * r2 * r2 / (r2 * r2 - r4 * r4));
  const Real angle = std::atan2(state.frame[0][3], state.frame[0][2]);
  const Real spread = (largest - smallest) / std::abs(expected);
  std::printf("driven ring: torque %.6e N m/m over the last second (spread %.1e of it), expected %.6e (%+.3f %%); "
              "force (%.1e, %.1e) N/m; turned %.6f rad for %.6f\n",
              torque, spread, expected, 100 * (torque / expected - 1), state.fluid_force[0].x(), state.fluid_force[0].y(),
              angle, Omega * dt * steps);
  EXPECT_LT(spread, 1e-4);
  EXPECT_NEAR(torque / expected, 1, 0.005);
  EXPECT_LT(state.fluid_force[0].head(2).norm(), 1e-9 * std::abs(expected));
  EXPECT_NEAR(angle, Omega * dt * steps, 1e-12);
}

TEST(ImmersedDrivenBody, TheSourcesJacobianIsTheDerivativeOfItsResidual) {
  // A disc driven across a swirling fluid velocity while turning: its frame does not depend on the
  // fluid, so the Jacobian is the direct term alone; every column the body touches matches central
  // differences of the residual (measured as the free body's, against the largest column, h = 1e-4).
  const NavierStokesModel m = test::closed_box_fluid(false);
  const PrescribedRigidMotion motion{[](Real t) { return Vec3(0.1, -0.2 * std::cos(t), 0); },
                                     [](Real t) { return Vec3(0, 0, 0.5 + t); }};
  const ImmersedSolids solids = test::one_rigid_body(disc_mesh(Vec3(0.5, 1, 0), 0.1, 8, 3), m.density, m, 0.01, motion);
  ImmersedSolidState state = initial_immersed_state(solids);
  state.time = 0.3;
  ImmersedCoupling coupling(m, solids, state);
  VectorX x, x_n;
  test::swirling_velocities_2d(m, x, x_n);
  for (FlowIntegrator scheme : {FlowIntegrator::midpoint, FlowIntegrator::backward_euler}) {
    const FlowTimeStep step{scheme, 0.01, &x_n, &x_n};
    const auto [worst, columns] = test::source_jacobian_against_differences(coupling, m, x, step, 1e-4, true);
    std::printf("driven body source Jacobian: %d columns, largest difference %.2e of the largest column\n", columns, worst);
    EXPECT_GT(columns, 50);
    EXPECT_LT(worst, 1e-8);
  }
}

TEST(ImmersedDrivenBody, ABodyDrivenOutOfTheFluidStopsTheStepSayingSo) {
  // A disc driven at 50 m/s leaves the 1 m box within a 0.01 s step: the step fails, and its
  // message names the body and the node that left, not only a residual that is not finite.
  NavierStokesModel m;
  m.mesh = make_rectangle_mesh(Vec2(0, 0), Vec2(1, 1), {8, 8}, ElementType::quad4);
  m.density = 1;
  m.viscosity = 0.01;
  for (const char* side : {"left", "right", "bottom", "top"}) prescribe_velocity(m, side, [](const Vec3&) { return Vec3::Zero(); });
  fix_pressure(m, 0);
  setup_navier_stokes(m);
  const PrescribedRigidMotion motion{[](Real) { return Vec3(50, 0, 0); }, [](Real) { return Vec3::Zero(); }};
  const ImmersedSolids solids = test::one_rigid_body(disc_mesh(Vec3(0.5, 0.5, 0), 0.1, 4, 2), m.density, m, 0.01, motion);
  ImmersedSolidState state = initial_immersed_state(solids);
  ImmersedCoupling coupling(m, solids, state);
  VectorX x = VectorX::Zero(m.dof_count());
  FlowStepper stepper(FlowIntegrator::backward_euler);
  FlowLinearSolver solver;
  const FlowSolveResult r = stepper.step(m, 0, 0.01, x, solver, {}, &coupling);
  std::printf("failure: %s\n", r.failure.c_str());
  EXPECT_FALSE(r.converged);
  EXPECT_NE(r.failure.find("rigid body 'body': node"), std::string::npos);
  EXPECT_NE(r.failure.find("left the fluid's mesh"), std::string::npos);
}

TEST(ImmersedDrivenBody, TheLoadOnAFreeBodyIsItsMassTimesAccelerationLessGravity) {
  // The load is computed from the coupling's forces and the inertia of the fluid the body holds;
  // for a free body its equations make it M_s (acceleration - g) (Newton's law; the constraint
  // forces have no resultant and no moment). A disc three times denser than the fluid falls from
  // rest in a closed box for 20 steps of 0.01 s: per step the load matches m ((v_n+1 - v_n)/dt - g)
  // to round-off: the frame's equations are solved to round-off for the step's final fluid velocity
  // (the tolerance, 1e-9, leaves room for the fluid inertia's and the coupling's cancellation).
  const NavierStokesModel m = test::closed_box_fluid(true);
  const Real dt = 0.01, rho_s = 3;
  const ImmersedSolids solids = test::one_rigid_body(disc_mesh(Vec3(0.4, 1, 0), 0.1, 8, 3), rho_s, m, dt);
  const Eigen::MatrixXd body_mass = solids.rigid_bodies[0].excess_mass + solids.rigid_bodies[0].fluid_mass;
  const Real mass = body_mass(0, 0);
  ImmersedSolidState state = initial_immersed_state(solids);
  ImmersedCoupling coupling(m, solids, state);
  VectorX x = VectorX::Zero(m.dof_count());
  FlowStepper stepper(FlowIntegrator::midpoint);
  FlowLinearSolver solver;
  Real worst = 0;
  for (int step = 0; step < 20; ++step) {
    const VectorX before = state.frame_velocity[0];
    const FlowSolveResult r = stepper.step(m, dt * step, dt, x, solver, {.tolerance = 1e-12}, &coupling);
    ASSERT_TRUE(r.converged) << r.failure;
    if (step == 0) continue;  // the midpoint rule starts with two half steps: the load is the second's
    const Vec3 acceleration((state.frame_velocity[0][0] - before[0]) / dt, (state.frame_velocity[0][1] - before[1]) / dt, 0);
    const Vec3 newton = mass * (acceleration - m.body_force);
    worst = std::max(worst, (state.fluid_force[0] - newton).norm() / newton.norm());
  }
  std::printf("free disc's load: %.6f N/m upwards against its weight %.6f N/m; largest difference from Newton's law %.1e\n",
              state.fluid_force[0].y(), mass * 9.81, worst);
  EXPECT_LT(worst, 1e-9);
  EXPECT_GT(state.fluid_force[0].y(), 0);
}

}  // namespace
}  // namespace moreau
