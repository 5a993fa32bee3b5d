// The flow's equations with an immersed rigid body in them (fem/flow/flow_source_assembly): the
// whole Jacobian, the stabilization's dependence on the body's force density included, against
// central differences of the residual (the deformable solid's case is in test_immersed_coupling).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "flow_source_jacobian.hpp"
#include "flow_test_helpers.hpp"
#include "immersed_rigid_body_fixtures.hpp"
#include "immersed_test_meshes.hpp"
#include "moreau/fem/flow/flow_source_assembly.hpp"
#include "moreau/fem/immersed/immersed_coupling.hpp"

namespace moreau {
namespace {

TEST(FlowSourceAssembly, TheJacobianWithAnImmersedBodyIsTheDerivativeOfTheResidual) {
  // A free disc three times denser than the fluid, moving and turned, in a swirling fluid velocity,
  // one midpoint step: the residual R(v) = R_cells(v, f(v)) + R_src(v) with the force density
  // f = -R_src / V in the SUPG/PSPG residual. Every column of the Jacobian (sparse part plus the
  // frame's U V^T) for the fluid dofs within 0.25 m of the disc matches central differences. tau
  // and nu_LSIC are held fixed (fixed_tau), as the assembly's Jacobian treats them; the
  // differences are measured against the largest column, as for the source alone (h = 1e-4 m/s;
  // its round-off divided by h is about 1e-10 of it).
  NavierStokesModel m = test::closed_box_fluid(true);
  m.fixed_tau = 2e-3;
  m.fixed_lsic = 1e-3;
  const Real dt = 0.01;
  const ImmersedSolids solids = test::one_rigid_body(test::disc_mesh(Vec3(0.5, 1, 0), 0.1, 8, 3), 3, m, dt);
  ImmersedSolidState state = initial_immersed_state(solids);
  const Real turn = 0.3;
  state.frame[0].segment(2, 2) = Vec2(std::cos(turn), std::sin(turn));
  state.frame[0].segment(4, 2) = Vec2(-std::sin(turn), std::cos(turn));
  state.frame_velocity[0] << 0.1, -0.2, -0.5 * std::sin(turn), 0.5 * std::cos(turn), -0.5 * std::cos(turn), -0.5 * std::sin(turn);
  ImmersedCoupling coupling(m, solids, state);
  VectorX x, x_n;
  test::swirling_velocities_2d(m, x, x_n);
  const FlowTimeStep step{FlowIntegrator::midpoint, dt, &x_n, &x_n};

  const auto [worst, columns] =
      test::flow_with_source_jacobian_against_differences(m, coupling, x, step, 1e-4, Vec3(0.5, 1, 0), 0.25);
  std::printf("flow with an immersed disc: %d columns, largest difference from central differences %.2e of the largest column\n",
              columns, worst);
  EXPECT_GT(columns, 200);
  EXPECT_LT(worst, 1e-8);
}

}  // namespace
}  // namespace moreau
