// The flow's PETSc path (the plugin libmoreau_petsc.so) against the direct one (UMFPACK): the same
// Newton solution with every preconditioner, steady and transient, and a clear failure when the
// Krylov solver cannot converge.
#include <gtest/gtest.h>

#include <cstdio>

#include "flow_test_helpers.hpp"
#include "immersed_released_block.hpp"
#include "moreau/fem/flow/flow_stepper.hpp"
#include "moreau/fem/petsc/petsc_presets.hpp"

namespace moreau {
namespace {

using test::lid_driven_cavity;

FlowLinearSettings petsc_settings(const std::string& preconditioner, Real tolerance) {
  FlowLinearSettings s;
  s.method = FlowLinearMethod::petsc;
  s.preconditioner = preconditioner;
  s.tolerance = tolerance;
  return s;
}

Real max_difference(const VectorX& a, const VectorX& b) { return (a - b).lpNorm<Eigen::Infinity>(); }

// Both Newton solves stop at |R| <= 1e-11 |R_0|, each Krylov solve at a residual 1e-10 times its
// right-hand side's: the two solutions then differ by about cond(J) 1e-11 |x| (cond(J) ~ 1e3 on
// these meshes; the lid speed is 1, the pressure ~0.1), below the 1e-8 the comparison asks for.
const FlowSolveSettings kTightNewton{.tolerance = 1e-11, .max_iterations = 30};

class PetscFlowPreconditioner : public testing::TestWithParam<std::string> {};

TEST_P(PetscFlowPreconditioner, GivesTheDirectSteadySolutionOfA2DCavity) {
  NavierStokesModel m = lid_driven_cavity(2, 16);
  VectorX direct = VectorX::Zero(m.dof_count()), iterative = direct;
  FlowLinearSolver lu;
  const FlowSolveResult a = solve_navier_stokes(m, 0, {}, direct, lu, kTightNewton);
  FlowLinearSolver petsc(petsc_settings(GetParam(), 1e-10));
  const FlowSolveResult b = solve_navier_stokes(m, 0, {}, iterative, petsc, kTightNewton);
  ASSERT_TRUE(a.converged) << a.failure;
  ASSERT_TRUE(b.converged) << b.failure;
  const FlowLinearStatistics& s = petsc.statistics();
  std::printf("2D cavity 16^2, %s: Newton %d (direct) vs %d, %ld Krylov iterations in %ld solves; max |dx| = %.2e\n",
              petsc.name().c_str(), a.iterations, b.iterations, s.iterations, s.solves,
              max_difference(direct, iterative));
  EXPECT_LT(max_difference(direct, iterative), 1e-8);
  EXPECT_EQ(s.solves, b.iterations);
}

INSTANTIATE_TEST_SUITE_P(EachPreset, PetscFlowPreconditioner, testing::ValuesIn(flow_petsc_preconditioners()));

TEST(PetscFlowSolver, FieldSplitGivesTheDirectSteadySolutionOfA3DCavity) {
  NavierStokesModel m = lid_driven_cavity(3, 8);
  VectorX direct = VectorX::Zero(m.dof_count()), iterative = direct;
  FlowLinearSolver lu;
  ASSERT_TRUE(solve_navier_stokes(m, 0, {}, direct, lu, kTightNewton).converged);
  FlowLinearSolver petsc(petsc_settings("fieldsplit", 1e-10));
  const FlowSolveResult r = solve_navier_stokes(m, 0, {}, iterative, petsc, kTightNewton);
  ASSERT_TRUE(r.converged) << r.failure;
  EXPECT_EQ(petsc.name(), "petsc fgmres+fieldsplit");
  EXPECT_LT(max_difference(direct, iterative), 1e-8);
}

TEST(PetscFlowSolver, GivesTheDirectTransientSolution) {
  // Five BDF2 steps (dt = 0.05 s) of the 2D cavity started impulsively, one solver object across
  // the steps; the states agree to 1e-8 after every step (as above).
  NavierStokesModel m = lid_driven_cavity(2, 24);
  VectorX direct = VectorX::Zero(m.dof_count()), iterative = direct;
  FlowLinearSolver lu, petsc(petsc_settings("fieldsplit", 1e-10));
  FlowStepper stepper_direct(FlowIntegrator::bdf2), stepper_iterative(FlowIntegrator::bdf2);
  for (int step = 0; step < 5; ++step) {
    const Real t = 0.05 * step;
    ASSERT_TRUE(stepper_direct.step(m, t, 0.05, direct, lu, kTightNewton).converged);
    const FlowSolveResult r = stepper_iterative.step(m, t, 0.05, iterative, petsc, kTightNewton);
    ASSERT_TRUE(r.converged) << r.failure;
    EXPECT_LT(max_difference(direct, iterative), 1e-8) << "step " << step + 1;
  }
}

TEST(PetscFlowSolver, GivesTheDirectStepsOfAFlowWithAnImmersedSolid) {
  // The stretched block released in a closed box (tests/fem/immersed): ten midpoint steps of
  // 0.01 s, the solid's terms in the Jacobian; the fluid's states agree to 1e-8 after every step,
  // as the cavities' above.
  test::ReleasedBlock direct = test::released_block(0.01), petsc = test::released_block(0.01);
  ImmersedCoupling coupling_direct(direct.fluid, direct.solids, direct.state);
  ImmersedCoupling coupling_petsc(petsc.fluid, petsc.solids, petsc.state);
  VectorX x_direct = VectorX::Zero(direct.fluid.dof_count()), x_petsc = x_direct;
  FlowStepper stepper_direct(FlowIntegrator::midpoint), stepper_petsc(FlowIntegrator::midpoint);
  FlowLinearSolver lu, krylov(petsc_settings("fieldsplit", 1e-10));
  for (int step = 0; step < 10; ++step) {
    const Real t = 0.01 * step;
    ASSERT_TRUE(stepper_direct.step(direct.fluid, t, 0.01, x_direct, lu, kTightNewton, &coupling_direct).converged);
    const FlowSolveResult r = stepper_petsc.step(petsc.fluid, t, 0.01, x_petsc, krylov, kTightNewton, &coupling_petsc);
    ASSERT_TRUE(r.converged) << r.failure;
    EXPECT_LT(max_difference(x_direct, x_petsc), 1e-8) << "step " << step + 1;
  }
  EXPECT_GT(x_direct.lpNorm<Eigen::Infinity>(), 1e-3) << "the block set the fluid moving";
}

TEST(PetscFlowSolver, AKrylovSolveThatCannotConvergeFailsWithPetscsReason) {
  // Two iterations of unpreconditioned GMRES cannot reduce the residual 1e-12 times on the
  // cavity: the linear solve fails, and Newton reports PETSc's reason instead of taking a bad step.
  NavierStokesModel m = lid_driven_cavity(2, 16);
  FlowLinearSettings settings = petsc_settings("ilu", 1e-12);
  settings.max_iterations = 2;
  settings.petsc_options = "-pc_type none";
  FlowLinearSolver petsc(settings);
  VectorX x = VectorX::Zero(m.dof_count());
  const FlowSolveResult r = solve_navier_stokes(m, 0, {}, x, petsc, kTightNewton);
  EXPECT_FALSE(r.converged);
  EXPECT_NE(r.failure.find("DIVERGED_ITS after 2 iterations"), std::string::npos) << r.failure;
}

TEST(PetscFlowSolver, OptionsGivenTwiceTakeTheLast) {
  // The user's options come after the preset's: "-pc_type lu" replaces the field split.
  NavierStokesModel m = lid_driven_cavity(2, 8);
  FlowLinearSettings settings = petsc_settings("fieldsplit", 1e-10);
  settings.petsc_options = "-ksp_type gmres -pc_type lu";
  FlowLinearSolver petsc(settings);
  VectorX x = VectorX::Zero(m.dof_count());
  ASSERT_TRUE(solve_navier_stokes(m, 0, {}, x, petsc, kTightNewton).converged);
  EXPECT_EQ(petsc.name(), "petsc gmres+lu");
  // One Krylov iteration per solve: an exact LU leaves nothing to iterate.
  EXPECT_EQ(petsc.statistics().iterations, petsc.statistics().solves);
}

}  // namespace
}  // namespace moreau
