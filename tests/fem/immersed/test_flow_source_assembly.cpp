// The flow's equations with an immersed body in them (fem/flow/flow_source_assembly): the whole
// Jacobian, the stabilization's dependence on the body's force density included, against central
// differences of the residual.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "flow_source_jacobian.hpp"
#include "flow_test_helpers.hpp"
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
  NavierStokesModel m;
  m.mesh = make_rectangle_mesh(Vec2(0, 0), Vec2(1, 1.5), {24, 36}, ElementType::quad4);
  m.density = 1;
  m.viscosity = 0.01;
  m.body_force = Vec3(0, -9.81, 0);
  m.fixed_tau = 2e-3;
  m.fixed_lsic = 1e-3;
  for (const char* side : {"left", "right", "bottom", "top"})
    test::prescribe_velocity(m, side, [](const Vec3&) { return Vec3::Zero(); });
  test::fix_pressure(m, 0);
  setup_navier_stokes(m);
  const Real dt = 0.01;
  ImmersedSolids solids;
  solids.model.dim = 2;
  FemSolid solid;
  solid.name = "disc";
  solid.mesh = test::disc_mesh(Vec3(0.5, 1, 0), 0.1, 8, 3);
  solid.material.density = 3;
  add_fem_solid(solids.model, std::move(solid));
  finalize_fem_model(solids.model);
  solids.viscosity.push_back(m.viscosity);
  solids.rigid_bodies.push_back(make_immersed_rigid_body(solids.model, 0, m.density, default_rigid_coupling_stiffness(m, dt)));
  ImmersedSolidState state = initial_immersed_state(solids);
  const Real turn = 0.3;
  state.frame[0].segment(2, 2) = Vec2(std::cos(turn), std::sin(turn));
  state.frame[0].segment(4, 2) = Vec2(-std::sin(turn), std::cos(turn));
  state.frame_velocity[0] << 0.1, -0.2, -0.5 * std::sin(turn), 0.5 * std::cos(turn), -0.5 * std::cos(turn), -0.5 * std::sin(turn);
  ImmersedCoupling coupling(m, solids, state);
  VectorX x, x_n;
  test::swirling_velocities_2d(m, x, x_n);
  const FlowTimeStep step{FlowIntegrator::midpoint, dt, &x_n, &x_n};

  double seconds = 0;
  auto residual = [&](const VectorX& at) {
    VectorX R;
    assemble_flow_with_source(m, at, step, coupling, {}, R, nullptr, nullptr, seconds);
    return gather_free(m.free_index, m.free_count, R);
  };
  VectorX R;
  SparseMatrix J;
  FlowLowRank low_rank;
  assemble_flow_with_source(m, x, step, coupling, {}, R, &J, &low_rank, seconds);
  ASSERT_EQ(low_rank.U.cols(), 6);
  const Eigen::MatrixXd UV = low_rank.U * low_rank.V.transpose();
  Real largest = 0;
  for (int k = 0; k < J.outerSize(); ++k) largest = std::max(largest, (VectorX(J.col(k)) + UV.col(k)).norm());
  const Real h = 1e-4;
  Real worst = 0;
  int columns = 0;
  for (Index n = 0; n < m.mesh.node_count(); ++n) {
    if ((m.mesh.nodes[n] - Vec3(0.5, 1, 0)).norm() > 0.25) continue;
    for (int i = 0; i < 2; ++i) {
      const Index d = m.dof(n, i), column = m.free_index[d];
      if (column < 0) continue;
      VectorX plus = x, minus = x;
      plus[d] += h;
      minus[d] -= h;
      const VectorX difference = (residual(plus) - residual(minus)) / (2 * h);
      const VectorX exact = VectorX(J.col(column)) + UV.col(column);
      worst = std::max(worst, (exact - difference).norm() / largest);
      ++columns;
    }
  }
  std::printf("flow with an immersed disc: %d columns, largest difference from central differences %.2e of the largest column\n",
              columns, worst);
  EXPECT_GT(columns, 200);
  EXPECT_LT(worst, 1e-8);
}

}  // namespace
}  // namespace moreau
