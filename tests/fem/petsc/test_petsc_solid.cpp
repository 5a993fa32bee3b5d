// A solid's tangent systems on PETSc (the plugin libmoreau_petsc.so) against CHOLMOD/UMFPACK: the
// same static and dynamic Newton solutions with every preconditioner.
#include <gtest/gtest.h>

#include <cstdio>

#include "fem_test_helpers.hpp"
#include "moreau/fem/petsc/petsc_presets.hpp"
#include "moreau/fem/solids/dynamic_solver.hpp"
#include "moreau/fem/solids/fem_assembly.hpp"
#include "moreau/fem/solids/static_solver.hpp"

namespace moreau {
namespace {

// A 0.4 x 0.1 x 0.1 m Neo-Hookean block (E = 1 MPa, nu = 0.3) in 8 x 2 x 2 hex8 cells, clamped at
// x = 0 and bent by a shear traction of 20 kPa on x = 0.4: the tip moves 0.29 m, three quarters
// of the length, far into the geometrically nonlinear range (11 Newton iterations).
FemModel bent_block() {
  FemModel model;
  add_fem_solid(model, test::fem_solid("block", make_box_mesh(Vec3(0, 0, 0), Vec3(0.4, 0.1, 0.1), {8, 2, 2},
                                                              ElementType::hex8),
                                       test::fem_material(HyperelasticModel::neo_hookean, 1e6, 0.3)));
  test::prescribe_nodes(model, test::boundary_global_nodes(model, 0, "left"), [](const Vec3&) { return Vec3::Zero(); });
  test::add_traction(model, 0, "right", Vec3(0, 2e4, 0));
  finalize_fem_model(model);
  return model;
}

SolidLinearSettings petsc_settings(const std::string& preconditioner) {
  return {.petsc = true, .preconditioner = preconditioner, .tolerance = 1e-12, .max_iterations = 1000};
}

// Both Newton solves stop at a residual 1e-11 of the load; each Krylov solve at 1e-12 of its
// right-hand side. The displacements then differ by about cond(K) 1e-11 |u| (cond(K) ~ 1e3 on this
// mesh), below the 1e-8 |u| asked for.
const NewtonSettings kTightNewton{.tolerance = 1e-11, .max_iterations = 30};

class PetscSolidPreconditioner : public testing::TestWithParam<std::string> {};

TEST_P(PetscSolidPreconditioner, GivesTheDirectStaticSolution) {
  const FemModel model = bent_block();
  VectorX direct = VectorX::Zero(model.dof_count()), petsc = direct;
  SparseSymmetricSolver cholmod, krylov;
  krylov.use_petsc(petsc_settings(GetParam()), solid_unknown_layout(model));
  const NewtonResult a = solve_static(model, 1.0, direct, cholmod, kTightNewton);
  const NewtonResult b = solve_static(model, 1.0, petsc, krylov, kTightNewton);
  ASSERT_TRUE(a.converged) << a.failure;
  ASSERT_TRUE(b.converged) << b.failure;
  const Real scale = direct.lpNorm<Eigen::Infinity>();
  std::printf("bent block, %s: Newton %d vs %d, %ld Krylov iterations (at most %d per solve); largest |u| %.4f m, "
              "max |du| / |u| = %.2e\n",
              krylov.method().c_str(), a.iterations, b.iterations, krylov.krylov_iterations(),
              krylov.max_krylov_iterations(), scale, (direct - petsc).lpNorm<Eigen::Infinity>() / scale);
  EXPECT_GT(scale, 0.1) << "the load bends the block far";
  EXPECT_LT((direct - petsc).lpNorm<Eigen::Infinity>(), 1e-8 * scale);
  EXPECT_EQ(b.iterations, a.iterations) << "an accurate linear solve keeps Newton's quadratic convergence";
}

INSTANTIATE_TEST_SUITE_P(EachPreset, PetscSolidPreconditioner, testing::ValuesIn(solid_petsc_preconditioners()));

TEST(PetscSolidSolver, APrescribedDisplacementIsCarriedInByThePredictorAsWithCholmod) {
  // The block's free end pulled 0.1 m along x in two load steps (a Dirichlet value that changes
  // with the load factor): each step starts with the linearised predictor solve, then Newton. The
  // displacements agree to 1e-8 of the largest, as above.
  FemModel model;
  add_fem_solid(model, test::fem_solid("block", make_box_mesh(Vec3(0, 0, 0), Vec3(0.4, 0.1, 0.1), {8, 2, 2},
                                                              ElementType::hex8),
                                       test::fem_material(HyperelasticModel::neo_hookean, 1e6, 0.3)));
  test::prescribe_nodes(model, test::boundary_global_nodes(model, 0, "left"), [](const Vec3&) { return Vec3::Zero(); });
  for (Index node : test::boundary_global_nodes(model, 0, "right"))
    model.prescribed.push_back({model.dof(node, 0), [](Real t) { return 0.1 * t; }});
  finalize_fem_model(model);
  VectorX direct = VectorX::Zero(model.dof_count()), petsc = direct;
  SparseSymmetricSolver cholmod, krylov;
  krylov.use_petsc(petsc_settings("amg"), solid_unknown_layout(model));
  for (Real t : {0.5, 1.0}) {
    ASSERT_TRUE(solve_static(model, t, direct, cholmod, kTightNewton).converged);
    const NewtonResult r = solve_static(model, t, petsc, krylov, kTightNewton);
    ASSERT_TRUE(r.converged) << r.failure;
  }
  EXPECT_NEAR(direct.lpNorm<Eigen::Infinity>(), 0.1, 1e-12);
  EXPECT_LT((direct - petsc).lpNorm<Eigen::Infinity>(), 1e-8 * 0.1);
}

TEST(PetscSolidSolver, AmgGivesTheDirectEnergyMomentumSteps) {
  // The energy-momentum scheme's tangent is not symmetric: it goes to GMRES around the same
  // multigrid. The block, released from its bent shape with the load removed, swings for five
  // steps of 5 ms; the states agree to 1e-8 of the displacement after every step.
  FemModel model = bent_block();
  model.loads.clear();
  VectorX bent = VectorX::Zero(model.dof_count());
  SparseSymmetricSolver cholmod, krylov;
  krylov.use_petsc(petsc_settings("amg"), solid_unknown_layout(model));
  {
    const FemModel loaded = bent_block();
    ASSERT_TRUE(solve_static(loaded, 1.0, bent, cholmod, kTightNewton).converged);
  }
  const SparseMatrix mass = assemble_mass_matrix(model);
  FemDynamicState direct = initial_dynamic_state(model), petsc = direct;
  direct.u = petsc.u = bent;
  for (int step = 0; step < 5; ++step) {
    ASSERT_TRUE(step_dynamic(model, mass, StepRule::energy_momentum, 0.005, direct, cholmod, kTightNewton).converged);
    const NewtonResult r = step_dynamic(model, mass, StepRule::energy_momentum, 0.005, petsc, krylov, kTightNewton);
    ASSERT_TRUE(r.converged) << r.failure;
    EXPECT_LT((direct.u - petsc.u).lpNorm<Eigen::Infinity>(), 1e-8 * bent.lpNorm<Eigen::Infinity>()) << "step " << step;
  }
  EXPECT_EQ(krylov.method(), "petsc gmres+gamg");
  EXPECT_GT((direct.u - bent).norm(), 1e-3 * bent.norm()) << "the block moved";
}

}  // namespace
}  // namespace moreau
