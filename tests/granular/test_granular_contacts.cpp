// Granular media ("kind": "granular"): grains as particles touching each other and the ground.
// Restitution against the ground and between grains, frictionless grains spreading flat, and a
// pile that stands taller the more friction its grains have.
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

// A column of 3159 grains (r = 5 mm, 0.1 x 0.4 x 0.1 m) released on the ground. Without friction
// the grains slide apart into one layer (their tops within a diameter of the ground); with friction
// they stand as a pile whose height and angle of repose grow with mu.
struct Pile {
  Real top, angle;  // m, degrees
};

Pile settled_pile(Real mu) {
  World w = World::from_json(fmt::format(
      R"({{"name": "pile", "settings": {{"dt": 0.005, "substeps": 10, "duration": 2}},
      "objects": [{{"name": "ground", "kind": "collider", "shape": {{"type": "plane"}}, "friction": {0}}},
                  {{"name": "sand", "kind": "granular", "blocks": [{{"min": [-0.05, 0, -0.05], "max": [0.05, 0.4, 0.05]}}],
                    "radius": 0.005, "density": 2600, "friction": {0}}}],
      "probes": [{{"name": "top", "type": "extent", "object": "sand", "axis": "y", "quantity": "max"}},
                 {{"name": "angle", "type": "angle_of_repose", "object": "sand"}}]}})",
      mu));
  for (int s = 0; s < 400; ++s) w.step();
  return {w.probe_values()[0], w.probe_values()[1]};
}

TEST(GranularContacts, FrictionlessGrainsSpreadFlatAndFrictionBuildsAPile) {
  std::vector<Pile> piles;
  for (Real mu : {0.0, 0.2, 0.5, 0.8}) piles.push_back(settled_pile(mu));
  std::printf("column of grains after 2 s: top %.4f m (mu 0), %.4f (0.2), %.4f (0.5), %.4f (0.8); angle of repose "
              "%.1f, %.1f, %.1f degrees (mu 0.2, 0.5, 0.8)\n", piles[0].top, piles[1].top, piles[2].top, piles[3].top,
              piles[1].angle, piles[2].angle, piles[3].angle);
  EXPECT_LT(piles[0].top, 0.015);  // one layer: tops at r = 5 mm, within a diameter
  EXPECT_LT(piles[1].top, piles[2].top);
  EXPECT_LT(piles[2].top, piles[3].top);
  EXPECT_LT(piles[1].angle, piles[2].angle);
  EXPECT_LT(piles[2].angle, piles[3].angle);
}

}  // namespace
}  // namespace moreau
