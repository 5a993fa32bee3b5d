// The flow's iterative linear path (GMRES with a lagged ILUT) against the direct one (UMFPACK):
// the same Newton solution, steady and transient, and a clear failure when GMRES cannot converge.
#include <gtest/gtest.h>

#include <cstdio>

#include "flow_test_helpers.hpp"
#include "moreau/fem/flow/flow_stepper.hpp"

namespace moreau {
namespace {

using test::lid_driven_cavity;

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
  // The ILU carries over from step to step: fewer ILUs than steps (measured 1 for 26 Jacobians;
  // an ILU per step, or per Newton iteration, would mean the lag does not work).
  EXPECT_LT(s.preconditioner_updates, 5);
}

// A tridiagonal matrix of size n with `diagonal` and `off` on the off-diagonals (both stored).
SparseMatrix tridiagonal(int n, Real diagonal, Real off) {
  std::vector<Eigen::Triplet<Real, int>> entries;
  for (int i = 0; i < n; ++i) {
    entries.emplace_back(i, i, diagonal);
    if (i > 0) entries.emplace_back(i, i - 1, off);
    if (i + 1 < n) entries.emplace_back(i, i + 1, off);
  }
  SparseMatrix A(n, n);
  A.setFromTriplets(entries.begin(), entries.end());
  return A;
}

TEST(FlowLinearSolver, AStaleIluIsReplacedWhenGmresFailsWithIt) {
  // The ILU of the identity (with a tridiagonal pattern) is exact for it; for the 1D Laplacian
  // (2, -1) with the same pattern it is no preconditioner at all, and GMRES cannot reach 1e-8 in
  // 5 iterations on 100 unknowns. The lagged ILU is used first, the solve fails, and it is
  // retried with the Laplacian's own ILUT, which is its exact LU (a tridiagonal factorizes
  // without fill), so GMRES converges in one iteration.
  FlowLinearSettings settings = gmres_settings();
  settings.tolerance = 1e-8;
  settings.max_iterations = 5;
  FlowLinearSolver solver(settings);
  const VectorX b = VectorX::Ones(100);
  VectorX x;
  const SparseMatrix identity = tridiagonal(100, 1, 0), laplacian = tridiagonal(100, 2, -1);
  ASSERT_TRUE(solver.factorize(identity));
  ASSERT_TRUE(solver.solve(b, x)) << solver.failure();
  EXPECT_LT((x - b).norm(), 1e-12);
  ASSERT_TRUE(solver.factorize(laplacian));
  EXPECT_EQ(solver.statistics().preconditioner_updates, 1) << "the identity's ILU is kept for the next matrix";
  ASSERT_TRUE(solver.solve(b, x)) << solver.failure();
  EXPECT_LT((laplacian * x - b).norm(), 1e-8 * b.norm());
  const FlowLinearStatistics& s = solver.statistics();
  EXPECT_EQ(s.solves, 2);
  EXPECT_EQ(s.retries, 1);
  EXPECT_EQ(s.preconditioner_updates, 2);
}

TEST(FlowLinearSolver, GmresThatCannotConvergeFailsTheSolveWithItsReason) {
  // Three iterations cannot reduce the residual 1e-12 times on this system: with an ILU fresh
  // from this Jacobian there is nothing to retry, the linear solve fails, and Newton reports why
  // instead of taking a bad step.
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
  EXPECT_EQ(gmres.statistics().solves, 1);
  EXPECT_EQ(gmres.statistics().retries, 0);
}

}  // namespace
}  // namespace moreau
