// Stabilized Q1Q1 Navier-Stokes: the Jacobian against finite differences, Poiseuille flow
// converging at second order, and the lid-driven cavity at Re = 100 against Ghia et al. (1982).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "data/ghia1982_re100.hpp"
#include "fem_test_helpers.hpp"
#include "flow_test_helpers.hpp"
#include "moreau/fem/flow/navier_stokes.hpp"

namespace moreau {
namespace {

using test::fix_pressure;
using test::prescribe_velocity;

// Newton with tau frozen: with tau and nu_LSIC held fixed (the model's test hook), the Jacobian
// must be the exact derivative of the residual, convection, SUPG test-function and PSPG terms
// included; checked by central differences (step 1e-6) at a random state (and random previous
// states), for every scheme. Tolerance 1e-7 of max|J|: truncation ~1e-12.
void expect_exact_jacobian(FemMesh mesh, const Vec3& body_force, unsigned seed) {
  for (FlowIntegrator integrator :
       {FlowIntegrator::steady, FlowIntegrator::backward_euler, FlowIntegrator::bdf2, FlowIntegrator::midpoint}) {
    NavierStokesModel m;
    m.mesh = mesh;
    m.density = 2;
    m.viscosity = 0.01;
    m.body_force = body_force;
    m.fixed_tau = 0.05;
    m.fixed_lsic = 0.02;
    setup_navier_stokes(m);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<Real> dist(-1, 1);
    VectorX x(m.dof_count()), x1(m.dof_count()), x2(m.dof_count());
    for (Index i = 0; i < x.size(); ++i) x[i] = dist(rng), x1[i] = dist(rng), x2[i] = dist(rng);
    const FlowTimeStep step{integrator, 0.01, &x1, &x2};
    VectorX R, Rp;
    SparseMatrix J;
    assemble_flow(m, x, step, R, &J);
    const Eigen::MatrixXd Jd(J);
    const Real worst = test::jacobian_error(Jd, x, 1e-6, [&](const VectorX& v) {
      assemble_flow(m, v, step, Rp, nullptr);
      return Rp;
    });
    EXPECT_LT(worst, 1e-7 * Jd.cwiseAbs().maxCoeff()) << mesh.dim << "D, integrator " << static_cast<int>(integrator);
  }
}

TEST(NavierStokes, JacobianIsTheDerivativeOfTheResidual) {
  expect_exact_jacobian(make_rectangle_mesh(Vec2(0, 0), Vec2(1, 1), {3, 3}, ElementType::quad4), Vec3(0.3, -1, 0), 1);
}

TEST(NavierStokes, JacobianIsTheDerivativeOfTheResidualIn3D) {
  // Trilinear cells, four fields per node.
  expect_exact_jacobian(make_box_mesh(Vec3(0, 0, 0), Vec3(1, 0.8, 1.2), {2, 2, 2}, ElementType::hex8),
                        Vec3(0.3, -1, 0.2), 3);
}

TEST(NavierStokes, PoiseuilleFlowConvergesAtSecondOrder) {
  // A 2 x 1 channel, mu = 0.1, rho = 1, the parabola u = 4 U y (1 - y) (U = 1) prescribed at inlet
  // and outlet, no-slip walls, pressure 0 at the outlet's lower corner. The exact solution is
  // the parabola with dp/dx = -8 mu U. The parabola is not in Q1, so the velocity error is
  // O(h^2). Here the pressure gradient balances the viscous term entirely, and r_M drops the
  // viscous second derivatives (standard for Q1): PSPG then perturbs the solution by O(tau grad p),
  // also O(h^2) but with a large constant (14 % at 4 cells across). Measured rates 1.73, 1.89,
  // 1.96 towards 2; the pressure gradient within 0.5 % at 32 cells.
  std::vector<Real> errors;
  for (int n : {4, 8, 16, 32}) {
    NavierStokesModel m;
    m.mesh = make_rectangle_mesh(Vec2(0, 0), Vec2(2, 1), {2 * n, n}, ElementType::quad4);
    m.viscosity = 0.1;
    auto parabola = [](const Vec3& X) { return Vec3(4 * X.y() * (1 - X.y()), 0, 0); };
    prescribe_velocity(m, "bottom", [](const Vec3&) { return Vec3::Zero(); });
    prescribe_velocity(m, "top", [](const Vec3&) { return Vec3::Zero(); });
    prescribe_velocity(m, "left", parabola);
    prescribe_velocity(m, "right", parabola);
    fix_pressure(m, 2 * n);  // (2, 0)
    setup_navier_stokes(m);
    VectorX x = VectorX::Zero(m.dof_count());
    FlowLinearSolver solver;
    const NewtonResult r = solve_navier_stokes(m, 0, {}, x, solver, {.tolerance = 1e-10, .max_iterations = 20});
    ASSERT_TRUE(r.converged) << r.failure;
    Vec3 centre, left;
    Real p_mid, p_left;
    ASSERT_TRUE(test::sample_flow(m, x, Vec3(1, 0.5, 0), centre, p_mid));
    ASSERT_TRUE(test::sample_flow(m, x, Vec3(0.5, 0.5, 0), left, p_left));
    errors.push_back(std::abs(centre.x() - 1.0));
    const Real gradient = (p_mid - p_left) / 0.5;
    std::printf("Poiseuille %2d cells across: centre velocity error %.3e, dp/dx %.5f (exact %.5f), %d Newton\n", n,
                errors.back(), gradient, -0.8, r.iterations);
    if (n == 32) {
      EXPECT_NEAR(gradient, -0.8, 0.005 * 0.8);
    }
  }
  for (size_t k = 1; k < errors.size(); ++k) EXPECT_GT(std::log2(errors[k - 1] / errors[k]), 1.7);
  EXPECT_GT(std::log2(errors[2] / errors[3]), 1.9);
}

TEST(NavierStokes, LidDrivenCavityAtRe100MatchesGhia) {
  // The unit cavity, lid speed 1, rho = 1, mu = 0.01
  // (Re = 100), pressure 0 at the bottom-left corner, 64 x 64 quads, steady Newton from rest.
  // Every one of Ghia et al.'s 17 + 17 centreline values is matched within 0.02 of the lid speed
  // (the criterion); measured: see the printout.
  // The lid's corner nodes belong to the walls (u = 0), as in Ghia et al. (with the corners moving
  // too, the Re = 1000 cavity deviates 0.042 instead of 0.009).
  const int n = 64;
  NavierStokesModel m = test::lid_driven_cavity(2, n);
  VectorX x = VectorX::Zero(m.dof_count());
  FlowLinearSolver solver;
  const NewtonResult r = solve_navier_stokes(m, 0, {}, x, solver, {.tolerance = 1e-10, .max_iterations = 30});
  ASSERT_TRUE(r.converged) << r.failure;
  Real worst_u = 0, worst_v = 0;
  for (int k = 0; k < 17; ++k) {
    Vec3 u;
    Real p;
    ASSERT_TRUE(test::sample_flow(m, x, Vec3(0.5, test::ghia1982::kY[k], 0), u, p));
    worst_u = std::max(worst_u, std::abs(u.x() - test::ghia1982::kU100[k]));
    ASSERT_TRUE(test::sample_flow(m, x, Vec3(test::ghia1982::kX[k], 0.5, 0), u, p));
    worst_v = std::max(worst_v, std::abs(u.y() - test::ghia1982::kV100[k]));
  }
  std::printf("cavity Re = 100, %d x %d: max |u - Ghia| %.4f, max |v - Ghia| %.4f, %d Newton iterations (%.2f s assembly, "
              "%.2f s solve)\n",
              n, n, worst_u, worst_v, r.iterations, r.assembly_s, r.solve_s);
  EXPECT_LT(worst_u, 0.02);
  EXPECT_LT(worst_v, 0.02);
}

}  // namespace
}  // namespace moreau
