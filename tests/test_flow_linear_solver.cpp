// The flow's iterative linear path (GMRES with a lagged ILUT) against the direct one (UMFPACK):
// the same Newton solution, steady and transient, and a clear failure when GMRES cannot converge.
#include <gtest/gtest.h>

#include <cstdio>

#include "flow_test_helpers.hpp"
#include "moreau/fem/flow_stepper.hpp"

namespace moreau {
namespace {

using test::fix_pressure;
using test::prescribe_velocity;

// The lid-driven cube (lid y = 1 moving in x at 1 m/s, rho = 1, mu = 0.01: Re = 100), or the
// unit square in 2D.
NavierStokesModel lid_driven_cavity(int dim, int n) {
  NavierStokesModel m;
  m.mesh = dim == 3 ? make_box_mesh(Vec3(0, 0, 0), Vec3(1, 1, 1), {n, n, n}, ElementType::hex8)
                    : make_rectangle_mesh(Vec2(0, 0), Vec2(1, 1), {n, n}, ElementType::quad4);
  m.viscosity = 0.01;
  for (const FemBoundary& b : m.mesh.boundaries)
    if (b.name != "top") prescribe_velocity(m, b.name, [](const Vec3&) { return Vec3::Zero(); });
  // The lid's edge nodes are on the walls too; prescribed once, at rest (Ghia's convention).
  std::vector<bool> on_wall(m.mesh.node_count(), false);
  for (const FemBoundary& b : m.mesh.boundaries)
    if (b.name != "top")
      for (Index node : m.mesh.boundary_nodes(b.name)) on_wall[node] = true;
  for (Index node : m.mesh.boundary_nodes("top"))
    if (!on_wall[node])
      for (int k = 0; k < dim; ++k) m.prescribed.push_back({m.dof(node, k), [k](Real) { return k == 0 ? 1.0 : 0.0; }});
  fix_pressure(m, 0);
  setup_navier_stokes(m);
  return m;
}

FlowLinearSettings gmres_settings() {
  FlowLinearSettings s;
  s.method = FlowLinearMethod::gmres;
  return s;
}

Real max_difference(const VectorX& a, const VectorX& b) { return (a - b).lpNorm<Eigen::Infinity>(); }

TEST(FlowLinearSolver, GmresGivesTheDirectSteadySolutionOfA3DCavity) {
  // Both Newton solves stop at |R| <= 1e-10 |R_0|; the two solutions may then differ by about
  // cond(J) * 1e-10 |x|, far below 1e-7 (the lid speed is 1, the pressure ~0.1). Newton is
  // inexact with GMRES (forcing term 1e-3) but converges linearly anyway with tau frozen, so it
  // may take at most two more iterations.
  NavierStokesModel m = lid_driven_cavity(3, 8);
  const FlowSolveSettings newton{.tolerance = 1e-10, .max_iterations = 30};
  VectorX direct = VectorX::Zero(m.dof_count()), iterative = direct;
  FlowLinearSolver lu;
  const FlowSolveResult a = solve_navier_stokes(m, 0, {}, direct, lu, newton);
  FlowLinearSolver gmres(gmres_settings());
  const FlowSolveResult b = solve_navier_stokes(m, 0, {}, iterative, gmres, newton);
  ASSERT_TRUE(a.converged) << a.failure;
  ASSERT_TRUE(b.converged) << b.failure;
  const FlowLinearStatistics& s = gmres.statistics();
  std::printf("3D cavity 8^3 (%ld free unknowns): Newton %d (direct) vs %d (gmres), %ld GMRES iterations in %ld solves, "
              "%d ILU computations; max |x_gmres - x_direct| = %.2e\n",
              static_cast<long>(m.free_count), a.iterations, b.iterations, s.iterations, s.solves,
              s.preconditioner_updates, max_difference(direct, iterative));
  EXPECT_LT(max_difference(direct, iterative), 1e-7);
  EXPECT_LE(b.iterations, a.iterations + 2);
  EXPECT_EQ(s.solves, b.iterations);
  // The lag: one ILU serves several Jacobians.
  EXPECT_LT(s.preconditioner_updates, s.solves);
}

TEST(FlowLinearSolver, GmresGivesTheDirectTransientSolution) {
  // Five BDF2 steps (dt = 0.05 s) of the 2D cavity started impulsively, one solver object across
  // the steps (the ILU carries over): the states agree to 1e-7 after every step, for the reason
  // given above.
  NavierStokesModel m = lid_driven_cavity(2, 24);
  const FlowSolveSettings newton{.tolerance = 1e-10, .max_iterations = 30};
  VectorX direct = VectorX::Zero(m.dof_count()), iterative = direct;
  FlowLinearSolver lu, gmres(gmres_settings());
  FlowStepper stepper_direct(FlowIntegrator::bdf2), stepper_iterative(FlowIntegrator::bdf2);
  for (int step = 0; step < 5; ++step) {
    const Real t = 0.05 * step;
    ASSERT_TRUE(stepper_direct.step(m, t, 0.05, direct, lu, newton).converged);
    const FlowSolveResult r = stepper_iterative.step(m, t, 0.05, iterative, gmres, newton);
    ASSERT_TRUE(r.converged) << r.failure;
    EXPECT_LT(max_difference(direct, iterative), 1e-7) << "step " << step + 1;
  }
  const FlowLinearStatistics& s = gmres.statistics();
  std::printf("2D cavity 24^2, 5 BDF2 steps: %ld GMRES iterations in %ld solves, %d ILU computations\n", s.iterations,
              s.solves, s.preconditioner_updates);
  EXPECT_LT(s.preconditioner_updates, 5);
}

TEST(FlowLinearSolver, GmresThatCannotConvergeFailsTheSolveWithItsReason) {
  // Three iterations cannot reduce the residual 1e-12 times on this system: the linear solve
  // fails, after one retry with a fresh ILU, and Newton reports why instead of taking a bad step.
  NavierStokesModel m = lid_driven_cavity(2, 16);
  FlowLinearSettings settings = gmres_settings();
  settings.tolerance = 1e-12;
  settings.max_iterations = 3;
  FlowLinearSolver gmres(settings);
  VectorX x = VectorX::Zero(m.dof_count());
  const FlowSolveResult r = solve_navier_stokes(m, 0, {}, x, gmres, {.picard_fallback = false});
  EXPECT_FALSE(r.converged);
  EXPECT_NE(r.failure.find("GMRES did not reach its tolerance"), std::string::npos) << r.failure;
  EXPECT_NE(r.failure.find("linear_solver"), std::string::npos) << r.failure;
}

}  // namespace
}  // namespace moreau
