// What a granular column collapse needs: grains filling a vertical cylinder, the `runout` probe
// of the deposit, and a container removed at a time (`until`, the tube lifted in an instant).
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "moreau/math/types.hpp"
#include "moreau/world.hpp"

namespace moreau {
namespace {

constexpr Real kR = 0.0025;        // grain radius, m
constexpr Real kCylinder = 0.05;   // m
constexpr Real kSpacing = 2 * kR * 1.02;

std::string cylinder_scene(const std::string& probes) {
  return fmt::format(
      R"({{"name": "column", "settings": {{"dt": 0.0025, "substeps": 5, "duration": 1, "gravity": [0, 0, 0]}},
      "objects": [{{"name": "sand", "kind": "granular", "radius": {},
                    "cylinders": [{{"base": [0.1, 0, -0.2], "radius": {}, "height": 0.03}}]}}],
      "probes": [{}]}})",
      kR, kCylinder, probes);
}

// The lattice points of the cylinder's bounding box whose grain lies inside: counted here from the
// lattice (spacing 2.04 r from a corner r in), every grain centre within R - r of the axis before
// its jitter of at most 1 % of r in each direction.
TEST(GranularColumns, ACylinderHoldsTheLatticeGrainsThatLieInside) {
  World w = World::from_json(cylinder_scene(""));
  const StateArray x = w.array("particle.position");
  const int across = static_cast<int>(std::floor((2 * kCylinder - 2 * kR) / kSpacing + 1 + 1e-9));
  const int layers = static_cast<int>(std::floor((0.03 - 2 * kR) / kSpacing + 1 + 1e-9));
  long expected = 0;
  for (int i = 0; i < across; ++i)
    for (int k = 0; k < across; ++k) {
      const Real dx = -kCylinder + kR + kSpacing * i, dz = -kCylinder + kR + kSpacing * k;
      if (std::hypot(dx, dz) <= kCylinder - kR) ++expected;
    }
  expected *= layers;
  std::printf("cylinder of radius %.3f m, 0.03 m tall: %ld grains (%d layers of %ld)\n", kCylinder, x.count, layers,
              expected / layers);
  EXPECT_EQ(x.count, expected);
  Real farthest = 0;
  for (long p = 0; p < x.count; ++p) {
    const Real rho = std::hypot(x.values[3 * p] - 0.1, x.values[3 * p + 2] + 0.2);
    farthest = std::max(farthest, rho);
    EXPECT_GE(x.values[3 * p + 1], kR * 0.99 - 1e-12);
    EXPECT_LE(x.values[3 * p + 1], 0.03 - kR * 0.99 + 1e-12);
  }
  EXPECT_LE(farthest, kCylinder - kR + std::sqrt(2.0) * 0.01 * kR + 1e-12);
}

// The probe against its definition evaluated here on the grains' positions: radially from the
// axis through `center`, and along a direction from it, for shares 1 and 0.5.
TEST(GranularColumns, TheRunoutProbeIsTheReachOfTheGivenShareOfTheGrains) {
  World w = World::from_json(cylinder_scene(
      R"({"name": "all", "type": "runout", "object": "sand", "center": [0.1, 5, -0.2], "fraction": 1},
         {"name": "half", "type": "runout", "object": "sand", "center": [0.1, 0, -0.2], "fraction": 0.5},
         {"name": "along", "type": "runout", "object": "sand", "center": [0.1, 0, 0], "direction": [2, 1, 0], "fraction": 1},
         {"name": "default", "type": "runout", "object": "sand"})"));
  const StateArray x = w.array("particle.position");
  std::vector<Real> radial, along;
  Vec3 mean = Vec3::Zero();
  for (long p = 0; p < x.count; ++p) {
    radial.push_back(std::hypot(x.values[3 * p] - 0.1, x.values[3 * p + 2] + 0.2) + kR);
    along.push_back(x.values[3 * p] - 0.1 + kR);  // the direction's horizontal part is +x
    mean += Vec3(x.values[3 * p], x.values[3 * p + 1], x.values[3 * p + 2]) / static_cast<Real>(x.count);
  }
  std::vector<Real> about_mean;
  for (long p = 0; p < x.count; ++p)
    about_mean.push_back(std::hypot(x.values[3 * p] - mean.x(), x.values[3 * p + 2] - mean.z()) + kR);
  std::sort(radial.begin(), radial.end());
  const std::vector<Real> probe = w.probe_values();
  const size_t half = static_cast<size_t>(std::ceil(0.5 * radial.size())) - 1;
  std::printf("runout of %zu grains: all %.6f m, half %.6f m, along +x %.6f m, about the centre of mass %.6f m\n",
              radial.size(), probe[0], probe[1], probe[2], probe[3]);
  EXPECT_DOUBLE_EQ(probe[0], radial.back());
  EXPECT_DOUBLE_EQ(probe[1], radial[half]);
  EXPECT_DOUBLE_EQ(probe[2], *std::max_element(along.begin(), along.end()));
  std::nth_element(about_mean.begin(), about_mean.begin() + static_cast<long>(std::ceil(0.99 * x.count)) - 1,
                   about_mean.end());
  EXPECT_NEAR(probe[3], about_mean[static_cast<size_t>(std::ceil(0.99 * x.count)) - 1], 1e-12);
}

// A 6 cm slab of grains held between a back wall and a gate (box colliders 1 m wide) that is
// removed at 0.3 s: no grain passes the gate's face before, and they slump out past where its
// far face stood after.
TEST(GranularColumns, AGateRemovedAtItsTimeReleasesTheGrains) {
  World w = World::from_json(
      R"({"name": "gate", "settings": {"dt": 0.0025, "substeps": 5, "duration": 1},
      "objects": [{"name": "ground", "kind": "collider", "shape": {"type": "plane"}},
                  {"name": "gate", "kind": "collider", "until": 0.3,
                   "shape": {"type": "box", "center": [0.055, 0.05, 0], "half_extents": [0.005, 0.05, 0.5]}},
                  {"name": "back", "kind": "collider",
                   "shape": {"type": "box", "center": [-0.055, 0.05, 0], "half_extents": [0.005, 0.05, 0.5]}},
                  {"name": "sand", "kind": "granular", "radius": 0.0025, "rolling_resistance": 0.1,
                   "blocks": [{"min": [-0.05, 0, -0.02], "max": [0.05, 0.06, 0.02]}]}],
      "probes": [{"name": "front", "type": "extent", "object": "sand", "axis": "x", "quantity": "max"}]})");
  Real held = 0;
  while (w.time() < 1 - 1e-9) {
    w.step();
    if (w.time() < 0.3 - 1e-9) held = std::max(held, w.probe_values()[0]);
  }
  const Real released = w.probe_values()[0];
  std::printf("gate removed at 0.3 s: the front grain at most %.4f m before (gate face at 0.05 m), %.4f m at 1 s\n", held,
              released);
  EXPECT_LE(held, 0.05 - 0.0025 + 1e-4);  // a grain's centre stays a radius inside the gate (within its overlap)
  EXPECT_GT(released, 0.06 + 0.0025);
}

// A removed collider is dropped from the particle contacts only: with a rigid body in the scene
// it is refused with its path.
TEST(GranularColumns, ARemovedColliderWithARigidBodyIsRefused) {
  try {
    World::from_json(R"({"name": "bad", "settings": {"dt": 0.001, "duration": 1},
        "objects": [{"name": "gate", "kind": "collider", "until": 0.5,
                     "shape": {"type": "box", "center": [0, 0, 0], "half_extents": [1, 1, 1]}},
                    {"name": "crate", "kind": "rigid_body", "shape": {"type": "box", "half_extents": [0.1, 0.1, 0.1]},
                     "position": [0, 3, 0]}]})");
    ADD_FAILURE() << "no error";
  } catch (const std::exception& e) {
    std::printf("%s\n", e.what());
    EXPECT_NE(std::string(e.what()).find("objects[0].until"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("'crate'"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace moreau
