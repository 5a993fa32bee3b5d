// Two-way coupling of the fluid with rigid bodies (samples on the body surface that move with it
// and pass the fluid's push back as a force and a moment): Archimedes and momentum.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "moreau/model/diagnostics.hpp"
#include "fluid_tank_checks.hpp"
#include "fluid_test_helpers.hpp"
#include "test_helpers.hpp"

namespace moreau {
namespace {

using test::run_steps;
using test::scene_from_json;

// A rigid slab (0.12 x 0.06 x 0.12 m) dropped onto 0.1 m of water in a 0.24 m square tank, as the
// soft slab of test_fluid_coupling.cpp (r = 6.25 mm, 2,888 particles); a wide slab floats flat.
std::string rigid_slab_scene(Real density) {
  return test::slab_tank_scene(fmt::format(R"({{"name": "slab", "kind": "rigid_body",
       "shape": {{"type": "box", "half_extents": [0.06, 0.03, 0.06]}}, "position": [0, 0.132, 0], "density": {}}})",
                                           density));
}

TEST(FluidRigidCoupling, BoxOfHalfTheWaterDensityFloatsHalfSubmerged) {
  // Archimedes: rho_s H = rho_w T, so a 0.06 m slab of 500 kg/m^3 floats with draft T = 0.03 m,
  // half its height. Draft = open-water surface minus the slab's bottom face, averaged over 0.3 s
  // after 1.2 s of settling (the slab still bobs by about 1 mm). Tolerance r / 2 = 3.1 mm, as for
  // the soft slab: the particle surface settles about r/2 below the lattice top. The slab stays
  // flat (metacentric height +25 mm): tilt below 2 degrees.
  Scene scene = scene_from_json(rigid_slab_scene(500));
  const auto [draft, tilt] = test::measure_flotation(scene);
  std::printf("rigid slab draft %.4f m (Archimedes 0.0300 m), tilt %.3f deg\n", draft, tilt);
  EXPECT_NEAR(draft, 0.03, 0.5 * 0.00625);
  EXPECT_LT(tilt, 2.0);
}

TEST(FluidRigidCoupling, DenseBoxSinks) {
  // 2000 kg/m^3: no equilibrium in the water; it reaches the floor (up to one trapped particle
  // layer, 1.5 r = 9.4 mm, as the dense soft slab) within 1 s.
  Scene scene = scene_from_json(rigid_slab_scene(2000));
  const Index body = scene.model.objects[scene.model.find_object("slab")].body;
  run_steps(scene, 250);
  const Real bottom = scene.state.rigid.position[body].y() - 0.03;
  std::printf("dense rigid slab bottom %.4f m above the floor\n", bottom);
  EXPECT_LT(bottom, 1.5 * 0.00625 + 1e-3);
}

const std::string kBlobHitsBox =
    test::blob_hits_box_scene(R"({"dt": 0.002, "substeps": 4, "gravity": [0, 0, 0]})");

TEST(FluidRigidCoupling, BlobHittingAFreeBoxConservesMomentum) {
  // No gravity: a blob of water at 1.5 m/s hits a free box off its centre line. Density reactions
  // and contacts are equal and opposite pairs, so the total linear momentum stays at its initial
  // value to round-off (1e-10 relative over 100 steps), while the box takes part of it and turns.
  Scene scene = scene_from_json(kBlobHitsBox);
  const Vec3 p0 = linear_momentum(scene.model, scene.state, -1);
  const Index box = scene.model.find_object("box");
  run_steps(scene, 100);
  const Vec3 p1 = linear_momentum(scene.model, scene.state, -1);
  const Vec3 box_momentum = linear_momentum(scene.model, scene.state, box);
  const Real spin = scene.state.rigid.angular_velocity[scene.model.objects[box].body].norm();
  std::printf("momentum before %.6e, after %.6e kg m/s; the box took %.4f kg m/s and spins at %.3f rad/s\n", p0.x(),
              p1.x(), box_momentum.x(), spin);
  EXPECT_GT(box_momentum.x(), 0.1 * p0.x());
  EXPECT_GT(spin, 0.1);
  EXPECT_LT((p1 - p0).norm(), 1e-10 * p0.norm());
}

TEST(FluidRigidCoupling, BitIdenticalForOneAndTwoThreads) {
  // Each body sums its samples' reactions in their fixed order, whatever the thread count.
  auto run = [](int threads) {
    Scene scene = scene_from_json(kBlobHitsBox, {fmt::format("settings.threads={}", threads)});
    run_steps(scene, 60);
    return std::make_pair(scene.state.rigid.position, scene.state.rigid.orientation);
  };
  const auto one = run(1), two = run(2);
  ASSERT_EQ(one.first.size(), two.first.size());
  for (std::size_t b = 0; b < one.first.size(); ++b) {
    EXPECT_EQ(one.first[b], two.first[b]);
    EXPECT_EQ(one.second[b].coeffs(), two.second[b].coeffs());
  }
}

}  // namespace
}  // namespace moreau
