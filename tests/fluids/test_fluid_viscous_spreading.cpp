// A viscous gravity current: a block of honey-like liquid (mu = 10 Pa s) released on a no-slip
// floor spreads as Huppert's (1982) similarity solution of lubrication theory once it is thin.
// The channel is 2 cm deep between free-slip side walls, so the flow is plane; the free-slip back
// wall at x = 0 is the current's symmetry plane. For a fixed area A (per unit width, on one side of
// that plane) the front moves as
//   x_N(t) = 1.411 (g A^3 / (3 nu))^(1/5) t^(1/5),
// the constant from h(x, t) = (3 (x_N^2 - x^2) / (10 K t))^(1/3) with K = g / (3 nu), whose area is
// A = 0.8413 (3 / (10 K t))^(1/3) x_N^(5/3) (0.8413 = int_0^1 (1 - s^2)^(1/3) ds), so
// x_N = (10 / 3)^(1/5) 0.8413^(-3/5) (K A^3)^(1/5) t^(1/5) = 1.4112 (K A^3)^(1/5) t^(1/5).
// Here the front moves at 3.3 cm/s at 1 s on a current 2.9 cm thick, and slows: Reynolds number
// U h / nu below 0.1 (0.03 by 3 s).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "test_helpers.hpp"

namespace moreau {
namespace {

constexpr Real kRadius = 0.002, kBlock = 0.064, kViscosity = 10, kDensity = 1000, kGravity = 9.81;

Scene spreading_block() {
  return test::scene_from_json(fmt::format(R"({{"name": "spreading", "settings": {{"dt": 0.01, "substeps": 5}},
    "objects": [
      {{"name": "channel", "kind": "collider", "inside": true,
        "shape": {{"type": "box", "center": [0.2, 0.04, 0.01], "half_extents": [0.2, 0.05, 0.01]}}}},
      {{"name": "floor", "kind": "collider", "fluid_friction": 1,
        "shape": {{"type": "box", "center": [0.2, -0.005, 0.01], "half_extents": [0.2, 0.005, 0.03]}}}},
      {{"name": "honey", "kind": "fluid", "particle_radius": {}, "viscosity": {}, "density": {}, "xsph": 0,
        "block": {{"min": [0, 0, 0], "max": [{}, {}, 0.02]}}}}]}})",
                                           kRadius, kViscosity, kDensity, kBlock, kBlock));
}

// The front: the farthest particle's centre plus its radius.
Real front(const FluidState& f) {
  Real x = 0;
  for (Index i = 0; i < f.count; ++i) x = std::max(x, f.position[i].x());
  return x + kRadius;
}

TEST(FluidViscosity, AViscousCurrentOnANoSlipFloorSpreadsAsHuppertsSimilaritySolution) {
  Scene scene = spreading_block();
  ASSERT_EQ(scene.state.fluid.count, 16 * 16 * 5);
  const Real nu = kViscosity / kDensity, area = kBlock * kBlock;
  const Real scale = 1.4112 * std::pow(kGravity * area * area * area / (3 * nu), 0.2);
  // Measured with 2 ms substeps: +1.7, +2.5 and +2.6 % at 1, 2 and 3 s (the block's slump has
  // passed by 1 s; the current is 4-5 particles thick by 3 s). The error is first order in the
  // substep: +6 to +11 % with 5 ms substeps, +0.4 to +0.6 % with 1 ms. Bound 5 %: twice the
  // measured error at this substep.
  Real at_one_second = 0, at_three_seconds = 0;
  for (int second = 1; second <= 3; ++second) {
    test::run_steps(scene, 100);
    const Real t = scene.state.time, x = front(scene.state.fluid), expected = scale * std::pow(t, 0.2);
    std::printf("t = %.1f s: front %.4f m, Huppert %.4f m (%+.1f %%)\n", t, x, expected, 100 * (x / expected - 1));
    EXPECT_NEAR(x / expected, 1, 0.05);
    (second == 1 ? at_one_second : at_three_seconds) = x;
  }
  // The growth exponent between 1 and 3 s: 1/5, measured 0.208 (the current still carries a little
  // of its release: the similarity solution is its long-time limit).
  const Real exponent = std::log(at_three_seconds / at_one_second) / std::log(3.0);
  std::printf("front growth exponent %.3f (Huppert 0.2)\n", exponent);
  EXPECT_NEAR(exponent, 0.2, 0.02);
}

}  // namespace
}  // namespace moreau
