// Cohesion of grains: a bond of strength F holds two grains together against a pull below F and
// lets go above it.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <cmath>
#include <string>
#include <vector>

#include "moreau/math/types.hpp"
#include "moreau/world.hpp"

namespace moreau {
namespace {

// A vertical chain of 8 grains (r = 5 mm, 2600 kg/m^3), each touching the next, hangs from its
// top grain, held by a joint to the world. The top bond carries the weight of the 7 grains below
// it, 7 m g; the others carry less. With F 5 % above 7 m g the chain hangs: its lowest grain
// stays within the bonds' reach (r/10 each, 3.5 mm for 7) of 14 r below the top grain's centre.
// 5 % below, the top bond lets go and the 7 grains fall together: free fall loads no bond, so
// they stay within 7 bonds' reach of touching. The margin, 5 %: XPBD's one Gauss-Seidel pass per
// substep loads the top bond a little over its static share (2 % above it, the chain breaks under
// xpbd; nmd holds it).
struct Hanging {
  Real stretch;  // m, how far the lowest grain hangs below 14 r under the top grain after 0.5 s
  Real spread;   // m, the gaps between the lower 7 grains, summed
};

Hanging hang(Real strength_over_weight, const std::string& solver) {
  const Real r = 0.005, m = 2600 * 4 * kPi / 3 * r * r * r, weight = 7 * m * 9.81;
  World w = World::from_json(fmt::format(
      R"({{"name": "chain", "settings": {{{}, "duration": 1}},
      "objects": [{{"name": "sand", "kind": "granular", "blocks": [{{"min": [0, 0, 0], "max": [0.0102, 0.0816, 0.0102]}}],
                    "radius": 0.005, "cohesion": {}}}],
      "joints": [{{"name": "hook", "type": "spherical", "bodies": ["world", {{"object": "sand", "vertex": 7}}],
                   "anchor": [0, 0.07, 0]}}]}})",
      solver, strength_over_weight * weight));
  StateArray x = w.array("particle.position");
  for (int k = 0; k < 8; ++k) x.values[3 * k] = x.values[3 * k + 2] = 0, x.values[3 * k + 1] = 0.07 - 2 * r * (7 - k);
  while (w.time() < 0.5 - 1e-9) w.step();
  Real spread = 0;
  for (int k = 0; k < 6; ++k) spread += (x.values[3 * (k + 1) + 1] - x.values[3 * k + 1]) - 2 * r;
  return {(x.values[3 * 7 + 1] - x.values[1]) - 14 * r, spread};
}

TEST(GranularCohesion, ABondHoldsBelowItsStrengthAndLetsGoAbove) {
  for (const std::string solver : {R"("dt": 0.005, "substeps": 10)", R"("solver": "nmd", "dt": 0.002)"}) {
    const Hanging holds = hang(1.05, solver), breaks = hang(0.95, solver);
    std::printf("chain of 8 grains hung from the top one (%s): bonds of 1.05 x 7 m g: the lowest grain %.4f mm below "
                "touching; 0.95 x 7 m g: %.3f m below, the falling 7 spread by %.4f mm\n",
                solver.substr(1, 20).c_str(), 1e3 * holds.stretch, breaks.stretch, 1e3 * breaks.spread);
    EXPECT_LT(std::abs(holds.stretch), 7 * 0.1 * 0.005) << solver;
    EXPECT_GT(breaks.stretch, 0.5 * 0.5 * 9.81 * 0.25) << solver;  // at least half the free fall of 0.5 s
    EXPECT_LT(std::abs(breaks.spread), 6 * 0.1 * 0.005) << solver;
  }
}

// Without cohesion the same chain falls away from its top grain at once.
TEST(GranularCohesion, DryGrainsDoNotHang) {
  const Hanging dry = hang(0, R"("dt": 0.005, "substeps": 10)");
  std::printf("the dry chain: the lowest grain %.3f m below touching after 0.5 s (free fall 1.226 m)\n", dry.stretch);
  EXPECT_NEAR(dry.stretch, 0.5 * 9.81 * 0.25, 0.01);
}

// A bond's reach without a bond is refused with its path (it would widen the pair search for nothing).
TEST(GranularCohesion, AReachWithoutABondIsRefused) {
  try {
    World::from_json(R"({"name": "bad", "settings": {"dt": 0.001, "duration": 1},
        "objects": [{"name": "sand", "kind": "granular", "blocks": [{"min": [0, 0, 0], "max": [0.1, 0.1, 0.1]}],
                     "radius": 0.01, "cohesion_distance": 0.001}]})");
    ADD_FAILURE() << "no error";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("objects[0].cohesion_distance"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace moreau
