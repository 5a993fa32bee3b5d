// Nonlinear elastodynamics: the energy-momentum scheme conserves energy and momenta of a free
// elastic body at a large step, where the implicit midpoint rule does not (Simo & Tarnow 1992).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "fem_test_helpers.hpp"
#include "moreau/fem/solids/dynamic_solver.hpp"

namespace moreau {
namespace {

// An L of two 1 m x 0.25 m arms meeting at the origin, in 0.05 m plane-strain quads: a 20 x 20
// grid on [0, 1]^2 without the cells of x > 0.25 and y > 0.25.
FemMesh l_shape_mesh() {
  FemMesh mesh = make_rectangle_mesh(Vec2(0, 0), Vec2(1, 1), {20, 20}, ElementType::quad4);
  remove_cells(mesh, {{Vec3(0.25, 0.25, -1), Vec3(2, 2, 1)}}, Vec3(0, 0, 0), Vec3(1, 1, 0));
  EXPECT_EQ(mesh.cell_count(), 175);
  EXPECT_EQ(mesh.boundary_nodes("right").size(), 6u);  // the horizontal arm's end
  EXPECT_EQ(mesh.boundary_nodes("cut").size(), 31u);   // the two inner edges, 15 cells each
  return mesh;
}

struct Flight {
  std::vector<Real> energy, angular, linear_x, linear_y;  // per step after the pulse
  bool failed = false;
  int step_failed = -1;
  int newton_iterations = 0;
};

// The L at rest, pushed for 0.5 s by a hat-shaped pulse (peak at 0.25 s) of nodal forces at the
// ends of its arms: +y at the horizontal arm's end, -x at the vertical arm's top, so that it both
// translates and spins; then free for `steps` steps of h.
Flight fly(StepRule rule, Real h, int steps) {
  FemModel model;
  model.dim = 2;
  add_fem_solid(model, test::fem_solid("L", l_shape_mesh(), test::fem_material(HyperelasticModel::neo_hookean, 1e5, 0.3)));
  auto pulse = [](Real t) { return t < 0.25 ? t / 0.25 : t < 0.5 ? (0.5 - t) / 0.25 : 0.0; };
  NodalLoad right{"right", {}, {}, [&](Real t) { return Vec3(0, 40 * pulse(t), 0); }};
  NodalLoad top{"top", {}, {}, [&](Real t) { return Vec3(-20 * pulse(t), 0, 0); }};
  for (Index n = 0; n < model.node_count; ++n) {
    const Vec3 X = model.reference_position(n);
    if (X.x() > 1 - 1e-9) right.nodes.push_back(n), right.weights.push_back(1);
    if (X.y() > 1 - 1e-9) top.nodes.push_back(n), top.weights.push_back(1);
  }
  model.loads = {right, top};
  finalize_fem_model(model);
  const SparseMatrix M = assemble_mass_matrix(model);
  FemDynamicState state = initial_dynamic_state(model);
  SparseSymmetricSolver solver;
  Flight flight;
  for (int s = 0; s < steps; ++s) {
    const NewtonResult r = step_dynamic(model, M, rule, h, state, solver, {.tolerance = 1e-12, .max_iterations = 30});
    if (!r.converged || !std::isfinite(state.energy)) {
      flight.failed = true;
      flight.step_failed = s;
      return flight;
    }
    flight.newton_iterations += r.iterations;
    if (state.time < 0.5 - 1e-9) continue;
    Vec3 p, L;
    momenta(model, state.u, state.v, p, L);
    flight.energy.push_back(kinetic_energy(model, state.v) + state.energy);
    flight.angular.push_back(L.z());
    flight.linear_x.push_back(p.x());
    flight.linear_y.push_back(p.y());
  }
  return flight;
}

Real max_relative_drift(const std::vector<Real>& series) {
  Real worst = 0;
  for (Real x : series) worst = std::max(worst, std::abs(x - series.front()));
  return worst / std::abs(series.front());
}

TEST(FemDynamics, EnergyMomentumSchemeConservesAFreeFlyingL) {
  // After the pulse no external force acts: energy, linear and angular momentum are constant.
  // h = 0.05 s is 10 times the wave-crossing time of a cell (c = sqrt(E/rho) = 10 m/s, 0.05 m
  // cells) and 1/50 of the fundamental bending period; 2000 steps (100 s). The energy-momentum
  // scheme conserves all three exactly up to Newton's tolerance (1e-13) and round-off, so the
  // drifts stay below 1e-9 (energy) and 1e-10 (angular momentum) relative.
  const Flight em = fly(StepRule::energy_momentum, 0.05, 2000);
  ASSERT_FALSE(em.failed) << "step " << em.step_failed;
  const Real energy_drift = max_relative_drift(em.energy), angular_drift = max_relative_drift(em.angular);
  std::printf("energy-momentum: energy %.6g J, drift %.2e; angular momentum %.6g, drift %.2e; %.2f Newton iterations/step\n",
              em.energy.front(), energy_drift, em.angular.front(), angular_drift, em.newton_iterations / 2000.0);
  EXPECT_LT(energy_drift, 1e-9);
  EXPECT_LT(angular_drift, 1e-10);
  EXPECT_LT(max_relative_drift(em.linear_y), 1e-10);
  EXPECT_GT(std::abs(em.angular.front()), 0.1);  // it does spin

  // The implicit midpoint rule at the same step: conserves momenta (its force is symmetric in
  // the stress too) but not energy, which grows until the step fails.
  const Flight mid = fly(StepRule::midpoint, 0.05, 1000);
  const Real mid_drift = mid.energy.empty() ? 0 : max_relative_drift(mid.energy);
  std::printf("midpoint: %s after %zu steps, energy drift %.2e\n", mid.failed ? "failed" : "ran",
              mid.energy.size(), mid_drift);
  EXPECT_TRUE(mid.failed || mid_drift > 1e-3);
}

}  // namespace
}  // namespace moreau

namespace moreau {
namespace {

TEST(FemDynamics, PrescribedRampMovesABodyRigidly) {
  // A hex8 block moving at c = 0.3 m/s in x with its left face prescribed to u_x = c t: the
  // exact motion is a rigid translation, so every node keeps v_x = c and no strain appears. The
  // prescribed dofs' velocities are the derivative of their values (a midpoint recursion started
  // from v = 0 there would alternate 2c, 0, 2c, ... and shake the block).
  FemModel model;
  model.dim = 3;
  add_fem_solid(model, test::fem_solid("b", make_box_mesh(Vec3(0, 0, 0), Vec3(0.4, 0.2, 0.2), {4, 2, 2}, ElementType::hex8),
                                       test::fem_material(HyperelasticModel::neo_hookean, 1e5, 0.3)));
  for (Index n : test::boundary_global_nodes(model, 0, "left"))
    model.prescribed.push_back({model.dof(n, 0), [](Real t) { return 0.3 * t; }});
  finalize_fem_model(model);
  const SparseMatrix M = assemble_mass_matrix(model);
  FemDynamicState state = initial_dynamic_state(model);
  // The free dofs get the body's velocity; the prescribed ones take theirs from the ramp.
  for (Index n = 0; n < model.node_count; ++n)
    if (model.free_index[model.dof(n, 0)] >= 0) state.v[model.dof(n, 0)] = 0.3;
  SparseSymmetricSolver solver;
  for (int k = 0; k < 50; ++k) {
    const NewtonResult r = step_dynamic(model, M, StepRule::energy_momentum, 0.02, state, solver, {.tolerance = 1e-12});
    ASSERT_TRUE(r.converged) << r.failure;
    for (Index n = 0; n < model.node_count; ++n) {
      ASSERT_NEAR(state.v[model.dof(n, 0)], 0.3, 1e-9) << "step " << k;
      ASSERT_NEAR(state.u[model.dof(n, 0)], 0.3 * state.time, 1e-9);
    }
    ASSERT_LT(state.energy, 1e-12);
  }
}

}  // namespace
}  // namespace moreau
