// Granular media ("kind": "granular"): grains as particles touching each other and the ground.
// Restitution against the ground and between grains, grains spreading flat without friction or
// rolling resistance, and a pile that stands steeper the more of either its grains have.
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

// One 5 mm grain dropped from 0.5 m onto the ground, e = 0.5 on both: the first rebound rises to
// e^2 h = 0.125 m (its centre, measured from r above the ground). Under xpbd restitution acts in
// the velocity pass after each substep; under nmd as the contact's target velocity.
TEST(GranularContacts, AGrainBouncesToESquaredItsDropHeight) {
  for (const std::string settings : {R"("dt": 0.001, "substeps": 4)", R"("solver": "nmd", "dt": 0.0005, "nmd": {"substeps": 2})"}) {
    World w = World::from_json(fmt::format(
        R"({{"name": "bounce", "settings": {{{}, "duration": 1}},
        "objects": [{{"name": "ground", "kind": "collider", "shape": {{"type": "plane"}}, "restitution": 0.5}},
                    {{"name": "grain", "kind": "granular", "blocks": [{{"min": [-0.005, 0.5, -0.005], "max": [0.005, 0.51, 0.005]}}],
                      "radius": 0.005, "restitution": 0.5}}],
        "probes": [{{"name": "y", "type": "center_of_mass", "object": "grain"}}]}})",
        settings));
    const Real r = 0.005, start = w.probe_values()[1] - r;
    Real lowest = 1, apex = 0;
    bool bounced = false;
    while (w.time() < 0.75) {
      w.step();
      const Real y = w.probe_values()[1] - r;
      if (y < lowest) lowest = y;
      if (lowest < 1e-3) bounced = true;
      if (bounced) apex = std::max(apex, y);
    }
    std::printf("grain dropped from %.4f m with e = 0.5 (%s): rebound %.5f m, e^2 h %.5f m (%+.2f %%)\n", start,
                settings.substr(1, 30).c_str(), apex, 0.25 * start, 100 * (apex / (0.25 * start) - 1));
    EXPECT_NEAR(apex / (0.25 * start), 1, 0.02) << settings;
  }
}

// Two grains of 5 mm meet head on at 1 m/s each, no gravity, e = 0.8: they part at e times their
// closing speed, and their momentum stays zero.
TEST(GranularContacts, TwoGrainsPartAtETimesTheirClosingSpeed) {
  World w = World::from_json(R"({"name": "pair", "settings": {"dt": 0.001, "substeps": 4, "duration": 0.1, "gravity": [0, 0, 0]},
      "objects": [{"name": "left", "kind": "granular", "blocks": [{"min": [-0.03, 0, 0], "max": [-0.02, 0.01, 0.01]}],
                   "radius": 0.005, "restitution": 0.8, "velocity": [1, 0, 0]},
                  {"name": "right", "kind": "granular", "blocks": [{"min": [0.02, 0, 0], "max": [0.03, 0.01, 0.01]}],
                   "radius": 0.005, "restitution": 0.8, "velocity": [-1, 0, 0]}],
      "probes": [{"name": "left", "type": "point", "object": "left", "vertex": 0, "quantity": "velocity"},
                 {"name": "right", "type": "point", "object": "right", "vertex": 0, "quantity": "velocity"},
                 {"name": "p", "type": "momentum", "object": "*"}]})");
  for (int s = 0; s < 100; ++s) w.step();
  const std::vector<double> v = w.probe_values();
  const Real parting = v[3] - v[0];
  std::printf("grains meeting at 2 m/s, e = 0.8: part at %.6f m/s (e x 2 = 1.6), momentum %.2e kg m/s\n", parting, v[6]);
  EXPECT_NEAR(parting, 1.6, 0.016);
  EXPECT_LT(std::abs(v[6]), 1e-12);
}

// A column of 3159 grains (r = 5 mm, 0.1 x 0.4 x 0.1 m) released on the ground and left 2 s to
// collapse. Without friction, or with friction but without rolling resistance (perfect spheres
// roll on), the grains spread into one layer (their tops within a diameter of the ground); with
// both they stand as a pile whose angle of repose grows with mu and with mu_r.
struct Pile {
  Real top, angle;  // m, degrees
};

Pile settled_pile(Real mu, Real mu_r, const char* solver = R"("substeps": 10)") {
  World w = World::from_json(fmt::format(
      R"({{"name": "pile", "settings": {{{2}, "dt": 0.005, "duration": 2}},
      "objects": [{{"name": "ground", "kind": "collider", "shape": {{"type": "plane"}}, "friction": {0}}},
                  {{"name": "sand", "kind": "granular", "blocks": [{{"min": [-0.05, 0, -0.05], "max": [0.05, 0.4, 0.05]}}],
                    "radius": 0.005, "density": 2600, "friction": {0}, "rolling_resistance": {1}}}],
      "probes": [{{"name": "top", "type": "extent", "object": "sand", "axis": "y", "quantity": "max"}},
                 {{"name": "angle", "type": "angle_of_repose", "object": "sand"}}]}})",
      mu, mu_r, solver));
  for (int s = 0; s < 400; ++s) w.step();
  return {w.probe_values()[0], w.probe_values()[1]};
}

TEST(GranularContacts, GrainsSpreadFlatWithoutFrictionOrRollingResistanceAndPileUpWithBoth) {
  const Pile frictionless = settled_pile(0, 0.5), rolling = settled_pile(0.5, 0);
  std::vector<Pile> by_friction, by_rolling;
  for (Real mu : {0.2, 0.5, 0.8}) by_friction.push_back(settled_pile(mu, 0.5));
  for (Real mu_r : {0.2, 1.0}) by_rolling.push_back(settled_pile(0.5, mu_r));
  std::printf("column of grains after 2 s: top %.4f m without friction, %.4f m without rolling resistance; "
              "with mu_r 0.5: angle of repose %.1f, %.1f, %.1f degrees at mu 0.2, 0.5, 0.8; with mu 0.5: %.1f, %.1f, "
              "%.1f degrees at mu_r 0.2, 0.5, 1.0\n",
              frictionless.top, rolling.top, by_friction[0].angle, by_friction[1].angle, by_friction[2].angle,
              by_rolling[0].angle, by_friction[1].angle, by_rolling[1].angle);
  EXPECT_LT(frictionless.top, 0.015);  // one layer: tops at r = 5 mm, within a diameter
  EXPECT_LT(rolling.top, 0.015);
  EXPECT_LT(by_friction[0].angle, by_friction[1].angle);
  EXPECT_LT(by_friction[1].angle, by_friction[2].angle);
  EXPECT_LT(by_rolling[0].angle, by_friction[1].angle);
  EXPECT_LT(by_friction[1].angle, by_rolling[1].angle);
}

// The same column under nmd (one velocity solve of 50 sweeps per 5 ms step), where grains turn
// against the ground and each other as under xpbd: without friction it spreads into one layer,
// without rolling resistance into a layer still spreading after 2 s with a grain or two resting in
// its pockets (top 13.0 mm), and with both the pile's angle grows with mu and mu_r
// (measured after 2 s: 3.3 degrees at mu 0.2; 13.4, 24.3, 32.7 degrees at mu_r 0.2, 0.5, 1.0).
TEST(GranularContacts, UnderNmdGrainsSpreadFlatWithoutFrictionOrRollingResistanceAndPileUpWithBoth) {
  constexpr const char* nmd = R"("solver": "nmd")";
  const Pile frictionless = settled_pile(0, 0.5, nmd), rolling = settled_pile(0.5, 0, nmd);
  const Pile low_friction = settled_pile(0.2, 0.5, nmd);
  std::vector<Pile> by_rolling;
  for (Real mu_r : {0.2, 0.5, 1.0}) by_rolling.push_back(settled_pile(0.5, mu_r, nmd));
  std::printf("nmd, column of grains after 2 s: top %.4f m without friction, %.4f m without rolling resistance; "
              "angle of repose %.1f degrees at mu 0.2, mu_r 0.5; with mu 0.5: %.1f, %.1f, %.1f degrees at mu_r 0.2, 0.5, "
              "1.0\n",
              frictionless.top, rolling.top, low_friction.angle, by_rolling[0].angle, by_rolling[1].angle,
              by_rolling[2].angle);
  EXPECT_LT(frictionless.top, 0.0075);  // one layer: tops at r = 5 mm
  EXPECT_LT(rolling.top, 0.015);        // at most a grain on the first layer
  EXPECT_LT(low_friction.angle, by_rolling[1].angle);
  EXPECT_LT(by_rolling[0].angle, by_rolling[1].angle);
  EXPECT_LT(by_rolling[1].angle, by_rolling[2].angle);
}

}  // namespace
}  // namespace moreau
