// The viscosity where two liquids meet (fluids/interface_viscosity.hpp): Couette flow across two
// layers of different viscosity, against the analytic profile whose shear stress is continuous
// through the interface.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "fluid_test_helpers.hpp"
#include "test_helpers.hpp"

namespace moreau {
namespace {

constexpr Real kGap = 0.04;     // m, H: wall to wall
constexpr Real kWallSpeed = 0.1;  // m/s, U

// The gap of viscous_gap_scene split at x = H/2 into two liquids of the same density: `inner`
// (x < H/2, next to the still wall) of viscosity mu_1 and `outer` (next to the wall sliding along y
// at U) of mu_2. r = 2 mm, 5 particles across each layer, no gravity, dt = 1/120 s in 10 substeps.
std::string two_layer_gap(Real inner_viscosity, Real outer_viscosity) {
  return fmt::format(R"({{"name": "layers", "settings": {{"dt": 0.008333333333333333, "substeps": 10, "gravity": [0, 0, 0]}},
    "objects": [
      {{"name": "box", "kind": "collider", "inside": true,
        "shape": {{"type": "box", "center": [0.02, 0.3, 0.012], "half_extents": [0.03, 0.4, 0.012]}}}},
      {{"name": "still", "kind": "collider", "fluid_friction": 1,
        "shape": {{"type": "box", "center": [-0.005, 0.3, 0.012], "half_extents": [0.005, 0.4, 0.03]}}}},
      {{"name": "moving", "kind": "collider", "fluid_friction": 1, "velocity": [0, {}, 0],
        "shape": {{"type": "box", "center": [0.045, 0.3, 0.012], "half_extents": [0.005, 0.4, 0.03]}}}},
      {{"name": "inner", "kind": "fluid", "particle_radius": 0.002, "viscosity": {}, "xsph": 0,
        "block": {{"min": [0, 0.3, 0], "max": [0.02, 0.5, 0.024]}}}},
      {{"name": "outer", "kind": "fluid", "particle_radius": 0.002, "viscosity": {}, "xsph": 0,
        "block": {{"min": [0.02, 0.3, 0], "max": [0.04, 0.5, 0.024]}}}}]}})",
                     kWallSpeed, inner_viscosity, outer_viscosity);
}

// Steady Couette flow through two layers of thickness H/2: the shear stress tau is the same in
// both, tau = U / (H/2 (1/mu_1 + 1/mu_2)), and the speed rises by tau/mu across each:
//   u(x) = tau x / mu_1                               x <= H/2
//        = tau H / (2 mu_1) + tau (x - H/2) / mu_2     x >  H/2
Real two_layer_couette_speed(Real x, Real mu_1, Real mu_2) {
  const Real half = 0.5 * kGap, tau = kWallSpeed / (half / mu_1 + half / mu_2);
  return x <= half ? tau * x / mu_1 : tau * half / mu_1 + tau * (x - half) / mu_2;
}

// The largest departure of a lattice layer's mean speed from the steady profile, over U, after
// `steps` steps; particles 5 cm or more from the column's ends.
Real worst_layer_error(Real mu_1, Real mu_2, int steps) {
  Scene scene = test::scene_from_json(two_layer_gap(mu_1, mu_2));
  test::run_steps(scene, steps);
  EXPECT_EQ(scene.state.fluid.viscosity_stats.unconverged, 0);
  const test::SliceSpeeds layers = test::slice_speeds(scene.state.fluid, kGap, 10, 0.35, 0.45);
  Real worst = 0;
  for (int k = 0; k < 10; ++k) {
    EXPECT_GT(layers.count[k], 0) << "layer " << k;
    const Real exact = two_layer_couette_speed(layers.x[k], mu_1, mu_2);
    std::printf("  layer %d at x = %.4f m: %.5f m/s against %.5f\n", k, layers.x[k], layers.speed[k], exact);
    worst = std::max(worst, std::abs(layers.speed[k] - exact) / kWallSpeed);
  }
  return worst;
}

TEST(FluidInterfaceViscosity, CouetteFlowThroughTwoLayersKeepsTheShearStressContinuous) {
  // mu_1 = 1 Pa s next to the still wall, mu_2 = 100 Pa s next to the sliding one (the densities
  // 1000 kg/m^3): the thin liquid takes 100/101 of the velocity jump. 0.3 s is 7 of the slowest
  // diffusion times, (H/2)^2 / (pi^2 nu_1) = 0.04 s, so the flow is steady to 1e-3 of U.
  // Measured: worst layer 1.9 % of U, the viscous liquid's first layer, whose kernel reaches across
  // the interface; the thin liquid's shear rate is 1.9 % high. With each particle's own viscosity in
  // its stress and the arithmetic mean in the pairs it was 5.0 % (the thin liquid's shear rate 4.4 %
  // high: the viscous particles at the interface stiffened the thin liquid beside them); at a ratio
  // of 10 (1 and 10 Pa s) 1.9 % against 3.0 %. Bound 3 %: the interface's kernel-wide error of the
  // new treatment with margin, and well below the old treatment's 5 %, so the test fails if the
  // viscous particles at the interface stiffen their neighbours again.
  const Real worst = worst_layer_error(1, 100, 36);
  std::printf("two-layer Couette, viscosities 1 and 100 Pa s: worst layer %.2f %% of U\n", 100 * worst);
  EXPECT_LT(worst, 0.03);
}

}  // namespace
}  // namespace moreau
