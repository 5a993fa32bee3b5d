// The probes of piles and flows: the angle of repose of a cone of grains, and the mass that
// streams through a plane.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <cmath>
#include <random>
#include <vector>

#include "moreau/math/types.hpp"
#include "moreau/world.hpp"

namespace moreau {
namespace {

// Grains placed on the surface of a cone of slope 30 degrees (radius 0.15 m, apex on the axis at
// x = z = 0.3 m), at random angles and at distances rho spread evenly over the radius: a ring of
// width 2r = 6 mm holds ~ 860 grains and its highest is at its inner edge, so every ring's height
// lies on the same line shifted by half a ring and the fitted slope is the cone's. The
// tolerance, 0.3 degrees, allows for rings cut unevenly by the flank's 20 % and 80 % bounds; the
// measured error is below 0.01 degrees.
TEST(GranularProbes, AngleOfReposeOfAConeIsItsSlope) {
  World w = World::from_json(R"({"name": "cone", "settings": {"dt": 0.001, "duration": 1},
      "objects": [{"name": "sand", "kind": "granular", "blocks": [{"min": [0, 0, 0], "max": [0.3, 0.06, 0.3]}],
                   "radius": 0.003}],
      "probes": [{"name": "angle", "type": "angle_of_repose", "object": "sand"},
                 {"name": "about_apex", "type": "angle_of_repose", "object": "sand", "center": [0.3, 0, 0.3], "bin": 0.01}]})");
  StateArray x = w.array("particle.position");
  const long n = static_cast<long>(x.values.size() / 3);
  const Real r = 0.003, radius = 0.15, slope = std::tan(30 * kPi / 180), height = radius * slope;
  std::mt19937_64 draw(7);
  for (long i = 0; i < n; ++i) {
    const Real rho = radius * (i + 0.5) / n, phi = 2 * kPi * static_cast<Real>(draw() >> 11) * 0x1.0p-53;
    const Real top = height - rho * slope;  // the grain's top on the cone: its centre r below
    x.values[3 * i] = 0.3 + rho * std::cos(phi);
    x.values[3 * i + 1] = top - r;
    x.values[3 * i + 2] = 0.3 + rho * std::sin(phi);
  }
  const std::vector<double> v = w.probe_values();
  std::printf("grains on a 30 degree cone (%ld): angle of repose %.3f degrees about the centre of mass, %.3f about the apex "
              "(rings of 1 cm)\n", n, v[0], v[1]);
  EXPECT_NEAR(v[0], 30, 0.3);
  EXPECT_NEAR(v[1], 30, 0.3);
}

// A block of grains streams without gravity at 2 m/s through the plane y = 0 (normal -y: the
// direction it moves). Each layer of 10 x 10 grains carries 100 m through the plane once; the
// lattice spacing is s = 2.04 r, so the mean rate is 100 m v / s. The rate's mean over the time the
// block takes to pass matches it (the slab estimator's mean is exact for a steady stream: a layer
// spends 2r/v in the slab of 2r), and its time integral equals the mass that went through (the
// "beyond" quantity), both within 1 % (the stream's head and tail cross the slab partly).
TEST(GranularProbes, MassFlowThroughAPlaneIsTheMassThatPasses) {
  World w = World::from_json(R"({"name": "stream", "settings": {"dt": 0.0005, "substeps": 1, "duration": 1, "gravity": [0, 0, 0]},
      "objects": [{"name": "sand", "kind": "granular", "blocks": [{"min": [0, 0.01, 0], "max": [0.102, 0.5, 0.102]}],
                   "radius": 0.005, "velocity": [0, -2, 0]}],
      "probes": [{"name": "rate", "type": "mass_flow", "object": "sand", "point": [0, 0, 0], "normal": [0, -1, 0]},
                 {"name": "through", "type": "mass_flow", "object": "sand", "point": [0, 0, 0], "normal": [0, -1, 0], "quantity": "beyond"},
                 {"name": "count", "type": "particle_count", "object": "sand"}]})");
  const Real r = 0.005, m = 2600 * 4 * kPi / 3 * r * r * r, v = 2, s = 2.04 * r;
  const Real total = w.probe_values()[2] * m;
  Real integral = 0, steady_sum = 0;
  int steady_samples = 0;
  const Real dt = w.dt();
  while (w.probe_values()[1] < total - 1e-12 && w.time() < 1) {  // the block passes in 0.25 s
    w.step();
    const std::vector<double> p = w.probe_values();
    integral += p[0] * dt;
    if (p[1] > 0.2 * total && p[1] < 0.8 * total) steady_sum += p[0], ++steady_samples;
  }
  for (int k = 0; k < 100; ++k) w.step(), integral += w.probe_values()[0] * dt;
  const Real steady = steady_sum / steady_samples, expected = 100 * m * v / s;
  std::printf("a stream of grains through a plane: mean rate %.5f kg/s (100 m v / s = %.5f, %+.2f %%); integral %.5f kg, "
              "mass passed %.5f kg (%+.2f %%)\n", steady, expected, 100 * (steady / expected - 1), integral, total,
              100 * (integral / total - 1));
  EXPECT_NEAR(steady / expected, 1, 0.01);
  EXPECT_NEAR(integral / total, 1, 0.01);
}

// A probe of the wrong object or without its plane is refused with the JSON path.
TEST(GranularProbes, BadProbesAreRefusedWithTheirPath) {
  auto message = [](const std::string& probe) {
    try {
      World::from_json(fmt::format(R"({{"name": "bad", "settings": {{"dt": 0.001, "duration": 1}},
          "objects": [{{"name": "ground", "kind": "collider", "shape": {{"type": "plane"}}}},
                      {{"name": "sand", "kind": "granular", "blocks": [{{"min": [0, 0, 0], "max": [0.1, 0.1, 0.1]}}], "radius": 0.01}}],
          "probes": [{}]}})", probe));
    } catch (const std::exception& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message(R"({"name": "a", "type": "angle_of_repose", "object": "ground"})").find("probes[0].object"), std::string::npos);
  EXPECT_NE(message(R"({"name": "a", "type": "angle_of_repose", "object": "ground"})").find("granular"), std::string::npos);
  EXPECT_NE(message(R"({"name": "a", "type": "angle_of_repose", "object": "sand", "bin": 0})").find("probes[0].bin"), std::string::npos);
  EXPECT_NE(message(R"({"name": "f", "type": "mass_flow", "object": "sand", "point": [0, 0, 0]})").find("probes[0].normal"), std::string::npos);
  EXPECT_NE(message(R"({"name": "f", "type": "mass_flow", "object": "sand", "normal": [0, 1, 0]})").find("probes[0].point"), std::string::npos);
  EXPECT_NE(message(R"({"name": "f", "type": "mass_flow", "object": "sand", "point": [0, 0, 0], "normal": [0, 0, 0]})").find("zero"), std::string::npos);
}

}  // namespace
}  // namespace moreau
