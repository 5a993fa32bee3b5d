// The particle fluids' wall friction at rigid bodies (`fluid_friction` on a rigid body,
// fluid_viscosity.hpp): a kinematic plate drives start-up Couette flow as a moving collider wall
// does, and a free plate sliding along a viscous layer gives its momentum to the liquid and
// keeps the total.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "moreau/model/diagnostics.hpp"
#include "fluid_test_helpers.hpp"
#include "test_helpers.hpp"

namespace moreau {
namespace {

using test::run_steps;
using test::scene_from_json;

constexpr Real kGap = 0.04;  // m, H: plate to plate
constexpr Real kDt = 1.0 / 120;
constexpr int kLayers = 10;  // lattice layers across the gap

// As the collider Couette test (test_fluid_viscosity.cpp), with the moving wall a kinematic rigid
// box sliding along y at U = 0.1 m/s: no gravity, mu = 10 Pa s, the still plate at x = 0 a
// no-slip collider. Start-up Couette flow:
//   u(x, t) = U x / H - sum_n 2 U / (n pi) (-1)^(n+1) sin(n pi x / H) exp(-n^2 pi^2 nu t / H^2).
// At t = 0.1 s (6 diffusion times H^2 / (pi^2 nu)) the collider version has every layer within
// 0.3 % of U and this one within 1.0 % (the layer at the plate lags by that much: the body's
// surface samples sit at the centroids of its sub-triangles, not on the collider's lattice); the
// bound is the same 2 % of U.
TEST(FluidRigidFriction, AKinematicPlateDrivesCouetteFlow) {
  const Real U = 0.1, nu = 1e-2;
  Scene scene = scene_from_json(test::viscous_gap_scene(R"({"name": "moving", "kind": "rigid_body", "kinematic": true,
       "fluid_friction": 1, "velocity": [0, 0.1, 0], "shape": {"type": "box", "half_extents": [0.005, 0.2, 0.03]},
       "position": [0.045, 0.4, 0.012]})"));
  run_steps(scene, 12);
  const Real t = 12 * kDt;
  const test::SliceSpeeds layers = test::slice_speeds(scene.state.fluid, kGap, kLayers, 0.35, 0.45);
  Real worst = 0;
  for (int k = 0; k < kLayers; ++k) {
    ASSERT_GT(layers.count[k], 0) << "layer " << k;
    worst = std::max(worst, std::abs(layers.speed[k] - test::couette_startup_speed(layers.x[k], t, U, kGap, nu)) / U);
  }
  std::printf("Couette behind a kinematic rigid plate at t = %.3f s: worst layer %.2f %% of U (wall layer %.4f, "
              "exact %.4f m/s)\n",
              t, 100 * worst, layers.speed[kLayers - 1], test::couette_startup_speed(layers.x[kLayers - 1], t, U, kGap, nu));
  EXPECT_LT(worst, 0.02);
}

// A free 0.2 kg plate sliding along y at 0.1 m/s beside a 0.192 kg layer of mu = 10 Pa s liquid at
// rest, every other wall free-slip, no gravity. Only the plate's fluid friction acts along y: the
// density constraint and the contacts push along the walls' normals, and the plate, which the
// settling liquid pushes against the tank's wall, meets it without friction. So the liquid's and
// the plate's y momenta sum to the start's, to the implicit solve's residual (1e-4 of a substep's
// viscous impulse; measured 2.0e-4 of the start's momentum, most of it in the first substep),
// and after 0.5 s (3 diffusion times H^2 / nu) liquid and plate move together at m U / (m + M): even
// behind a plate too heavy to slow, the layer's slowest mode, exp(-pi^2 nu t / (4 H^2)), is down
// to 4.5e-4 by then, and this plate, which slows as the liquid speeds up, settles faster.
TEST(FluidRigidFriction, AFreePlateDragsTheLiquidAlongAndKeepsTheMomentum) {
  const Real U = 0.1, plate = 0.2;
  Scene scene = scene_from_json(test::viscous_gap_scene(R"({"name": "plate", "kind": "rigid_body", "mass": 0.2,
       "fluid_friction": 1, "velocity": [0, 0.1, 0], "friction": 0, "shape": {"type": "box", "half_extents": [0.003, 0.15, 0.011]},
       "position": [0.043, 0.4, 0.012]})", "0", "0"));
  const Index body = scene.model.objects[scene.model.find_object("plate")].body;
  Real liquid = 0;
  for (Index i = 0; i < scene.state.fluid.count; ++i) liquid += scene.state.fluid.mass[i];
  const Real p0 = linear_momentum(scene.model, scene.state, -1).y();
  Real worst_drift = 0;
  for (int step = 0; step < 60; ++step) {  // 0.5 s
    run_steps(scene, 1);
    worst_drift = std::max(worst_drift, std::abs(linear_momentum(scene.model, scene.state, -1).y() - p0));
  }
  const Real together = plate * U / (plate + liquid);
  const Real plate_speed = scene.state.rigid.velocity[body].y();
  Real fluid_momentum = 0;
  for (Index i = 0; i < scene.state.fluid.count; ++i)
    fluid_momentum += scene.state.fluid.mass[i] * scene.state.fluid.velocity[i].y();
  const test::SliceSpeeds layers = test::slice_speeds(scene.state.fluid, kGap, kLayers, 0.35, 0.45);
  const Real slowest = *std::min_element(layers.speed.begin(), layers.speed.end());
  const Real fastest = *std::max_element(layers.speed.begin(), layers.speed.end());
  std::printf("free plate after 0.5 s: plate %.5f, liquid %.5f m/s (layers %.5f to %.5f) against m U / (m + M) = "
              "%.5f; y momentum drift at most %.2e of the start's\n",
              plate_speed, fluid_momentum / liquid, slowest, fastest, together, worst_drift / p0);
  // 1 %: the slowest mode's 6e-4 and the momentum's drift (measured: plate -0.14 %).
  EXPECT_NEAR(plate_speed / together, 1, 0.01);
  EXPECT_NEAR(fluid_momentum / liquid / together, 1, 0.01);
  EXPECT_LT(worst_drift / p0, 1e-3);
}

}  // namespace
}  // namespace moreau
