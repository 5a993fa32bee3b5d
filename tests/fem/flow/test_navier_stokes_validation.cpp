// Stabilized Q1Q1 Navier-Stokes against exact solutions: Kovasznay flow (spatial convergence of
// velocity and pressure), the Taylor-Green vortex (decay rate), the orders of the time
// integrators, and Ethier & Steinman's 3D Beltrami flow (hex8, transient, GMRES).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <optional>

#include "flow_test_helpers.hpp"
#include "moreau/fem/flow/flow_problem.hpp"
#include "moreau/fem/flow/flow_stepper.hpp"

namespace moreau {
namespace {

using test::ExactFlow;

// Kovasznay (1948): steady flow behind a grid, an exact solution of the Navier-Stokes equations,
// u = 1 - e^(l x) cos(2 pi y), v = l/(2 pi) e^(l x) sin(2 pi y), p = (1 - e^(2 l x)) / 2, with
// l = Re/2 - sqrt(Re^2/4 + 4 pi^2), nu = 1/Re, rho = 1.
ExactFlow kovasznay(Real reynolds) {
  const Real l = reynolds / 2 - std::sqrt(reynolds * reynolds / 4 + 4 * M_PI * M_PI);
  return {[l](const Vec3& X, Real) {
            const Real e = std::exp(l * X.x());
            return Vec3(1 - e * std::cos(2 * M_PI * X.y()), l / (2 * M_PI) * e * std::sin(2 * M_PI * X.y()), 0);
          },
          [l](const Vec3& X, Real) { return 0.5 * (1 - std::exp(2 * l * X.x())); }};
}

// Taylor-Green vortex in 2D: u = (-cos x sin y, sin x cos y) e^(-2 nu t),
// p = -(cos 2x + cos 2y) e^(-4 nu t) / 4 (rho = 1); kinetic energy decays as e^(-4 nu t).
ExactFlow taylor_green(Real nu) {
  return {[nu](const Vec3& X, Real t) {
            const Real f = std::exp(-2 * nu * t);
            return Vec3(-std::cos(X.x()) * std::sin(X.y()) * f, std::sin(X.x()) * std::cos(X.y()) * f, 0);
          },
          [nu](const Vec3& X, Real t) { return -0.25 * (std::cos(2 * X.x()) + std::cos(2 * X.y())) * std::exp(-4 * nu * t); }};
}

// Ethier & Steinman (1994), "Exact fully 3D Navier-Stokes solutions for benchmarking", Int. J.
// Numer. Meth. Fluids 19: a Beltrami flow (vorticity parallel to velocity) decaying as
// e^(-d^2 nu t), with a = pi/4, d = pi/2 (rho = 1):
//   u = -a [e^(ax) sin(ay + dz) + e^(az) cos(ax + dy)] e^(-d^2 nu t), v and w by the cyclic
//   shift x -> y -> z -> x, and
//   p = -a^2/2 [e^(2ax) + e^(2ay) + e^(2az) + 2 sin(ax + dy) cos(az + dx) e^(a(y+z))
//       + 2 sin(ay + dz) cos(ax + dy) e^(a(z+x)) + 2 sin(az + dx) cos(ay + dz) e^(a(x+y))] e^(-2 d^2 nu t).
// (Checked symbolically: divergence-free, momentum residual 0.)
ExactFlow ethier_steinman(Real nu) {
  const Real a = M_PI / 4, d = M_PI / 2;
  return {[=](const Vec3& X, Real t) {
            const Real x = X.x(), y = X.y(), z = X.z(), f = -a * std::exp(-d * d * nu * t);
            return Vec3(f * (std::exp(a * x) * std::sin(a * y + d * z) + std::exp(a * z) * std::cos(a * x + d * y)),
                        f * (std::exp(a * y) * std::sin(a * z + d * x) + std::exp(a * x) * std::cos(a * y + d * z)),
                        f * (std::exp(a * z) * std::sin(a * x + d * y) + std::exp(a * y) * std::cos(a * z + d * x)));
          },
          [=](const Vec3& X, Real t) {
            const Real x = X.x(), y = X.y(), z = X.z();
            return -a * a / 2 * std::exp(-2 * d * d * nu * t) *
                   (std::exp(2 * a * x) + std::exp(2 * a * y) + std::exp(2 * a * z) +
                    2 * std::sin(a * x + d * y) * std::cos(a * z + d * x) * std::exp(a * (y + z)) +
                    2 * std::sin(a * y + d * z) * std::cos(a * x + d * y) * std::exp(a * (z + x)) +
                    2 * std::sin(a * z + d * x) * std::cos(a * y + d * z) * std::exp(a * (x + y)));
          }};
}

TEST(NavierStokesValidation, KovasznayFlowConvergesInVelocityAndPressure) {
  // Re = 40 on [-0.5, 1] x [-0.5, 1.5] (the usual domain), the exact velocity on the boundary,
  // the pressure pinned at a corner (errors compare mean-free pressures), steady Newton.
  // Q1 velocity interpolation is O(h^2) in L2; the stabilized pressure is expected at O(h^1.5)
  // or better. Measured (12x16 .. 96x128): velocity rates 1.67, 1.72, 1.80 (rising toward 2; the
  // PSPG/SUPG residual lacks the viscous term, an O(tau nu) consistency error that shrinks with
  // h^2 once tau ~ h^2/nu), pressure 1.55, 1.66, 1.75. Asserted: every velocity rate > 1.6,
  // pressure > 1.45, and the finest velocity error below 4e-3 (measured 3.0e-3).
  const ExactFlow exact = kovasznay(40);
  std::vector<test::FlowErrors> errors;
  for (int k : {4, 8, 16, 32}) {
    NavierStokesModel m;
    m.mesh = make_rectangle_mesh(Vec2(-0.5, -0.5), Vec2(1, 1.5), {3 * k, 4 * k}, ElementType::quad4);
    m.viscosity = 1.0 / 40;
    test::prescribe_exact_velocity(m, exact);
    test::fix_pressure(m, 0);
    setup_navier_stokes(m);
    VectorX x = VectorX::Zero(m.dof_count());
    FlowLinearSolver solver;
    const FlowSolveResult r = solve_navier_stokes(m, 0, {}, x, solver, {.tolerance = 1e-10});
    ASSERT_TRUE(r.converged) << r.failure;
    errors.push_back(test::flow_errors(m, x, exact, 0));
    std::printf("Kovasznay %3d x %3d: L2 velocity error %.3e, pressure %.3e, %d Newton\n", 3 * k, 4 * k,
                errors.back().velocity, errors.back().pressure, r.iterations);
  }
  for (size_t i = 1; i < errors.size(); ++i) {
    const Real ru = std::log2(errors[i - 1].velocity / errors[i].velocity);
    const Real rp = std::log2(errors[i - 1].pressure / errors[i].pressure);
    std::printf("  rates velocity %.2f, pressure %.2f\n", ru, rp);
    EXPECT_GT(ru, 1.6);
    EXPECT_GT(rp, 1.45);
  }
  EXPECT_LT(errors.back().velocity, 4e-3);
}

TEST(NavierStokesValidation, KovasznayFlowExtrudedIn3DMatchesThe2DSolution) {
  // The hex8 path against the quad4 one: Kovasznay's flow (Re = 40) in the slab
  // [-0.5, 1] x [-0.5, 1.5] x [0, 0.25] (12 x 16 x 2 cells), the exact velocity on the four side
  // faces and slip (w = 0, u and v free) on the two z faces. The z-independent extension of the
  // 2D discrete solution (12 x 16 quads) then satisfies the 3D discrete equations exactly (tensor-
  // product cells, zero tangential traction), so the two must agree to the solver tolerance:
  // asserted to 1e-8 at every node, with w = 0.
  const ExactFlow exact = kovasznay(40);
  auto solve = [&](NavierStokesModel& m) {
    m.viscosity = 1.0 / 40;
    for (const char* side : {"left", "right", "bottom", "top"})
      test::prescribe_velocity(m, side, [&](const Vec3& X) { return exact.velocity(X, 0); });
    if (m.mesh.dim == 3)
      for (const char* side : {"back", "front"})
        for (Index n : m.mesh.boundary_nodes(side)) m.prescribed.push_back({m.dof(n, 2), [](Real) { return 0.0; }});
    test::fix_pressure(m, 0);
    setup_navier_stokes(m);
    VectorX x = VectorX::Zero(m.dof_count());
    FlowLinearSolver solver;
    const FlowSolveResult r = solve_navier_stokes(m, 0, {}, x, solver, {.tolerance = 1e-12});
    EXPECT_TRUE(r.converged) << r.failure;
    return x;
  };
  NavierStokesModel flat, slab;
  flat.mesh = make_rectangle_mesh(Vec2(-0.5, -0.5), Vec2(1, 1.5), {12, 16}, ElementType::quad4);
  slab.mesh = make_box_mesh(Vec3(-0.5, -0.5, 0), Vec3(1, 1.5, 0.25), {12, 16, 2}, ElementType::hex8);
  const VectorX x2 = solve(flat), x3 = solve(slab);
  Real worst = 0, w = 0;
  for (Index n = 0; n < slab.mesh.node_count(); ++n) {
    // The rectangle's node (i, j) is i + 13 j; cells are 0.125 wide.
    const Vec3& X = slab.mesh.nodes[n];
    const Index n2 = std::lround((X.x() + 0.5) / 0.125) + 13 * std::lround((X.y() + 0.5) / 0.125);
    ASSERT_LT((slab.mesh.nodes[n].head<2>() - flat.mesh.nodes[n2].head<2>()).norm(), 1e-12);
    for (int k = 0; k < 2; ++k) worst = std::max(worst, std::abs(x3[slab.dof(n, k)] - x2[flat.dof(n2, k)]));
    worst = std::max(worst, std::abs(x3[slab.dof(n, 3)] - x2[flat.dof(n2, 2)]));
    w = std::max(w, std::abs(x3[slab.dof(n, 2)]));
  }
  std::printf("Kovasznay slab (hex8) vs plane (quad4): max difference %.2e, max |w| %.1e\n", worst, w);
  EXPECT_LT(worst, 1e-8);
  EXPECT_LT(w, 1e-12);
}

// Runs the Taylor-Green vortex on [0, 2 pi]^2 (exact velocity on the boundary) to time T.
VectorX run_taylor_green(int cells, Real nu, FlowIntegrator integrator, Real dt, Real T, Real fixed_tau,
                         NavierStokesModel& m) {
  const ExactFlow exact = taylor_green(nu);
  m = NavierStokesModel();
  m.mesh = make_rectangle_mesh(Vec2(0, 0), Vec2(2 * M_PI, 2 * M_PI), {cells, cells}, ElementType::quad4);
  m.viscosity = nu;
  m.fixed_tau = fixed_tau;  // > 0: tau (and nu_LSIC = 0.01 m^2/s) independent of dt and the state
  m.fixed_lsic = fixed_tau > 0 ? 0.01 : 0;
  test::prescribe_exact_velocity(m, exact);
  test::fix_pressure(m, 0);
  setup_navier_stokes(m);
  VectorX x = test::exact_state(m, exact, 0);
  FlowLinearSolver solver;
  FlowStepper stepper(integrator);
  const long steps = std::lround(T / dt);
  for (long s = 0; s < steps; ++s) {
    const FlowSolveResult r = stepper.step(m, s * dt, dt, x, solver, {.tolerance = 1e-11});
    EXPECT_TRUE(r.converged) << r.failure;
  }
  return x;
}

TEST(NavierStokesValidation, TaylorGreenVortexDecaysAtTheViscousRate) {
  // nu = 0.1, the midpoint rule with dt = 0.05 to T = 1: the kinetic energy decays as
  // e^(-4 nu t), rate 0.4. Measured: 0.4030 on 32^2 and 0.4037 on 64^2 (+0.75 %, +0.91 %). The
  // excess does not fall with h: for this flow the strong residual without its viscous term is
  // r_M = du/dt = -2 nu u (convection balances the pressure gradient exactly), so SUPG/PSPG add
  // an O(tau nu) dissipation with tau limited by dt/2 and h/(2|u|), not by h^2/(4 nu); the same
  // term makes the L2 velocity error fall only at first order here (2.9e-2, 1.4e-2). Restoring the
  // viscous term by a recovered Laplacian (Jansen et al. 1999) is the known remedy, not done yet.
  // Asserted: the rate within 1.5 % of 4 nu on both meshes.
  const Real nu = 0.1, T = 1;
  std::vector<Real> excess;
  for (int cells : {32, 64}) {
    NavierStokesModel m;
    const VectorX x = run_taylor_green(cells, nu, FlowIntegrator::midpoint, 0.05, T, 0, m);
    const VectorX x0 = test::exact_state(m, taylor_green(nu), 0);
    const Real rate = -std::log(flow_kinetic_energy(m, x) / flow_kinetic_energy(m, x0)) / T;
    excess.push_back(rate / (4 * nu) - 1);
    std::printf("Taylor-Green %d^2: energy decay rate %.5f (exact %.5f), %+.2f %%, L2 velocity error %.3e\n", cells,
                rate, 4 * nu, 100 * excess.back(), test::flow_errors(m, x, taylor_green(nu), T).velocity);
  }
  EXPECT_LT(std::abs(excess[0]), 0.015);
  EXPECT_LT(std::abs(excess[1]), 0.015);
}

TEST(NavierStokesValidation, AStepperCopiedBeforeAStepUndoesItWhenAssignedBack) {
  // How a failed step is retried in substeps: a copy taken before the step, assigned back, must
  // leave the stepper as it was, its last step pointing at its own previous states (not the
  // copy's). Taylor-Green on 12^2, the midpoint rule: step, copy, step, restore, step again; the
  // two second steps must agree bit for bit, and with BDF2 (which reads two previous states) too.
  for (FlowIntegrator integrator : {FlowIntegrator::midpoint, FlowIntegrator::bdf2}) {
    NavierStokesModel m;
    run_taylor_green(12, 0.1, integrator, 0.05, 0, 0, m);
    VectorX x = test::exact_state(m, taylor_green(0.1), 0);
    FlowLinearSolver solver;
    FlowStepper stepper(integrator);
    ASSERT_TRUE(stepper.step(m, 0, 0.05, x, solver, {.tolerance = 1e-11}).converged);
    const VectorX after_one = x;
    std::optional<FlowStepper> saved(stepper);
    ASSERT_TRUE(stepper.step(m, 0.05, 0.05, x, solver, {.tolerance = 1e-11}).converged);
    const VectorX first_try = x;
    stepper = *saved;
    saved.reset();  // the restored stepper must not read the copy's storage
    x = after_one;
    ASSERT_TRUE(stepper.step(m, 0.05, 0.05, x, solver, {.tolerance = 1e-11}).converged);
    EXPECT_EQ((x - first_try).lpNorm<Eigen::Infinity>(), 0.0);
    ASSERT_NE(stepper.last_step().previous, nullptr);
    EXPECT_EQ(*stepper.last_step().previous, after_one);
  }
}

TEST(NavierStokesValidation, TimeIntegratorsConvergeAtTheirOrders) {
  // The temporal order, free of spatial error: on a fixed 12^2 Taylor-Green mesh with tau fixed
  // (tau otherwise depends on dt through tau2 = dt/2, which would change the spatial
  // discretization with dt), the solutions at T = 1 for dt, dt/2, dt/4 give the observed order
  // log2(|x_dt - x_dt/2| / |x_dt/2 - x_dt/4|): 1 for backward Euler, 2 for BDF2 and the
  // midpoint rule (with its damped start; see flow_stepper.hpp). Measured 0.994, 2.005, 2.002 for
  // dt = 0.05, 0.025, 0.0125. Asserted within 0.15 of those.
  const Real nu = 0.1, T = 1;
  for (auto [integrator, order] : {std::pair{FlowIntegrator::backward_euler, 1.0}, std::pair{FlowIntegrator::bdf2, 2.0},
                                   std::pair{FlowIntegrator::midpoint, 2.0}}) {
    NavierStokesModel m;
    VectorX x[3];
    for (int i = 0; i < 3; ++i) x[i] = run_taylor_green(12, nu, integrator, 0.05 / (1 << i), T, 0.05, m);
    // Compare the velocities only (the midpoint rule's pressure lives at t_{n+1/2}).
    VectorX d01 = x[0] - x[1], d12 = x[1] - x[2];
    for (Index n = 0; n < m.mesh.node_count(); ++n) d01[m.dof(n, 2)] = d12[m.dof(n, 2)] = 0;
    const Real observed = std::log2(d01.norm() / d12.norm());
    std::printf("integrator %d: observed temporal order %.3f (expected %.0f), differences %.3e, %.3e\n", static_cast<int>(integrator), observed, order, d01.norm(), d12.norm());
    EXPECT_NEAR(observed, order, 0.15);
  }
}

TEST(NavierStokesValidation, EthierSteinmanBeltramiFlowConvergesIn3D) {
  // The exact velocity on the faces of [-1, 1]^3, the exact initial velocity, nu = 0.1 m^2/s,
  // four midpoint steps of 1/160 s, hex8 cells (4^3, 8^3, 16^3), the linear systems by GMRES +
  // ILUT. The time error (O(dt^2 (d^2 nu)^2), ~1e-6 relative) is far below the spatial one, so the
  // L2 velocity error at T must fall at about second order. Measured rates 1.93, 1.79; asserted
  // > 1.7. Two known effects, both measured, keep this test at a small dt and few steps:
  // - The SUPG/PSPG residual lacks the viscous term (-mu lap u = mu d^2 u here), an O(tau mu d^2)
  //   consistency error; with dt = 0.025 tau is limited by dt/2 on every mesh and the 8^3 -> 16^3
  //   velocity rate drops to 1.42 (docs/validation.md).
  // - The interpolated initial velocity does not satisfy the discrete continuity equation; the
  //   first steps answer with a pressure transient of order 1/dt that the midpoint rule damps
  //   slowly, so after four steps the (midpoint) pressure error does not yet converge with h. It
  //   is printed, not asserted (after 20 steps of 0.025 s its rates are 2.05 and 1.59).
  const Real nu = 0.1, dt = 1.0 / 160;
  const int steps = 4;
  const Real T = steps * dt;
  const ExactFlow exact = ethier_steinman(nu);
  std::vector<test::FlowErrors> errors;
  for (int cells : {4, 8, 16}) {
    NavierStokesModel m;
    m.mesh = make_box_mesh(Vec3(-1, -1, -1), Vec3(1, 1, 1), {cells, cells, cells}, ElementType::hex8);
    m.viscosity = nu;
    test::prescribe_exact_velocity(m, exact);
    test::fix_pressure(m, 0);
    setup_navier_stokes(m);
    VectorX x = test::exact_state(m, exact, 0);
    FlowLinearSolver solver({.method = FlowLinearMethod::gmres});
    FlowStepper stepper(FlowIntegrator::midpoint);
    int newton = 0;
    for (int s = 0; s < steps; ++s) {
      const FlowSolveResult r = stepper.step(m, s * dt, dt, x, solver, {.tolerance = 1e-10});
      ASSERT_TRUE(r.converged) << r.failure;
      newton += r.iterations;
    }
    const test::FlowErrors velocity = test::flow_errors(m, x, exact, T);
    const test::FlowErrors pressure = test::flow_errors(m, x, exact, T - dt / 2);
    errors.push_back({velocity.velocity, pressure.pressure});
    std::printf("Ethier-Steinman %2d^3: L2 velocity error %.3e, pressure %.3e; %d Newton, %ld GMRES iterations\n", cells,
                errors.back().velocity, errors.back().pressure, newton, solver.statistics().iterations);
  }
  for (size_t i = 1; i < errors.size(); ++i) {
    const Real ru = std::log2(errors[i - 1].velocity / errors[i].velocity);
    const Real rp = std::log2(errors[i - 1].pressure / errors[i].pressure);
    std::printf("  rates velocity %.2f, pressure %.2f\n", ru, rp);
    EXPECT_GT(ru, 1.7);
  }
}

}  // namespace
}  // namespace moreau
