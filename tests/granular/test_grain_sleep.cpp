// Sleeping grains (settings.sleep): a settled layer falls asleep and stays exactly where it is; a
// grain rolling into it wakes it, whole, before they touch; after the impact all settle and sleep
// again; a velocity written to a sleeping grain wakes it; the same for one and two threads; bad
// sleep settings are refused with their path.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <cmath>
#include <string>
#include <vector>

#include "moreau/errors.hpp"
#include "moreau/math/types.hpp"
#include "moreau/world.hpp"

namespace moreau {
namespace {

// A layer of 7 x 7 grains (r = 5 mm) resting on the ground, and a pebble sent sliding towards it
// over the ground at 0.5 m/s (without rolling resistance) from 0.45 m away: friction soon has it
// rolling at 5/7 of that, and it reaches the layer after 1.25 s.
std::string layer_and_pebble(const std::string& sleep) {
  return fmt::format(
      R"({{"name": "sleep", "settings": {{"dt": 0.005, "substeps": 10, "duration": 3, {}}},
      "objects": [{{"name": "ground", "kind": "collider", "shape": {{"type": "plane"}}}},
                  {{"name": "layer", "kind": "granular", "blocks": [{{"min": [-0.04, 0, -0.04], "max": [0.04, 0.01, 0.04]}}],
                    "radius": 0.005, "friction": 0.5}},
                  {{"name": "pebble", "kind": "granular", "blocks": [{{"min": [-0.505, 0, -0.005], "max": [-0.495, 0.01, 0.005]}}],
                    "radius": 0.005, "friction": 0.5, "rolling_resistance": 0, "velocity": [0.5, 0, 0]}}],
      "probes": [{{"name": "layer_asleep", "type": "asleep", "object": "layer"}},
                 {{"name": "asleep", "type": "asleep", "object": "*"}},
                 {{"name": "pebble", "type": "center_of_mass", "object": "pebble"}},
                 {{"name": "layer", "type": "center_of_mass", "object": "layer"}}]}})",
      sleep);
}

std::vector<double> particle_values(World& w, const std::string& name) {
  const StateArray a = w.array(name);
  return std::vector<double>(a.values.begin(), a.values.end());
}

TEST(GrainSleep, ASettledLayerSleepsUntilARollingGrainReachesIt) {
  World w = World::from_json(layer_and_pebble(R"("sleep": {"speed": 0.01, "time": 0.2})"));
  // Settled and asleep well before the pebble arrives: every one of the 49 grains, frozen.
  while (w.time() < 0.8 - 1e-9) w.step();
  ASSERT_EQ(w.probe_values()[0], 49) << "the layer has not fallen asleep";
  const std::vector<double> x_before = particle_values(w, "particle.position");
  w.step();
  const std::vector<double> x_after = particle_values(w, "particle.position");
  const std::vector<double> v = particle_values(w, "particle.velocity");
  for (int k = 0; k < 49 * 3; ++k) {
    EXPECT_EQ(x_after[k], x_before[k]) << "a sleeping grain moved";
    EXPECT_EQ(v[k], 0.0) << "a sleeping grain has a velocity";
  }
  // The pebble wakes the layer before it touches it: within its contact reach (a grain's first
  // row is centred at x = -0.035 m, so the two touch once the pebble's centre passes -0.045 m).
  Real pebble_at_wake = 0;
  while (w.time() < 1.4 - 1e-9) {
    w.step();
    if (pebble_at_wake == 0 && w.probe_values()[0] == 0) pebble_at_wake = w.probe_values()[2];
  }
  std::printf("layer of 49 grains asleep at 0.8 s; woken by the rolling pebble at x = %.4f m (touching from -0.045 m)\n",
              pebble_at_wake);
  ASSERT_LT(pebble_at_wake, 0) << "the pebble did not wake the layer";
  EXPECT_LT(pebble_at_wake, -0.045);
  EXPECT_GT(pebble_at_wake, -0.06);
  // All 50 settle and sleep again.
  while (w.time() < 3 - 1e-9) w.step();
  std::printf("at 3 s: %g of 50 grains asleep, pebble at x = %.4f m\n", w.probe_values()[1], w.probe_values()[2]);
  EXPECT_EQ(w.probe_values()[1], 50);
}

// A controller that writes a sleeping grain's velocity through the state arrays sets it going:
// the grain's island wakes before the step, and the grain leaves with that velocity.
TEST(GrainSleep, AVelocityWrittenToASleepingGrainWakesIt) {
  World w = World::from_json(layer_and_pebble(R"("sleep": {"time": 0.2})"));
  while (w.time() < 0.8 - 1e-9) w.step();
  ASSERT_EQ(w.probe_values()[0], 49);
  const double y0 = particle_values(w, "particle.position")[1];
  w.array("particle.velocity").values[1] = 1.0;  // grain 0 thrown up at 1 m/s
  w.step();
  const std::vector<double> x = particle_values(w, "particle.position");
  std::printf("grain 0 thrown up from its sleep: %g grains of the layer asleep after the step, rose %.4f m\n",
              w.probe_values()[0], x[1] - y0);
  EXPECT_EQ(w.probe_values()[0], 0);
  // Free flight over 10 substeps of h = 0.5 ms (no contact holds a grain moving up and away):
  // v gains -g h before each move of h v, so the rise is 10 h v0 - 55 g h^2; rounding only.
  const Real h = 0.0005;
  EXPECT_NEAR(x[1] - y0, 10 * h * 1.0 - 55 * 9.81 * h * h, 1e-12);
}

TEST(GrainSleep, SleepingIsIndependentOfTheThreadCount) {
  std::vector<std::vector<double>> finals;
  for (int threads : {1, 2}) {
    World w = World::from_json(layer_and_pebble(R"("sleep": {"time": 0.2})"));
    while (w.time() < 1.5 - 1e-9) w.step(threads);
    std::vector<double> values = particle_values(w, "particle.position");
    const std::vector<double> probes = w.probe_values();
    values.insert(values.end(), probes.begin(), probes.end());
    finals.push_back(values);
  }
  EXPECT_TRUE(finals[0] == finals[1]);
}

TEST(GrainSleep, BadSleepSettingsAreRefusedWithTheirPath) {
  auto message = [](const std::string& sleep) {
    try {
      World::from_json(layer_and_pebble(sleep));
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(message(R"("sleep": {"speed": 0})").find("settings.sleep.speed"), std::string::npos);
  EXPECT_NE(message(R"("sleep": {"time": -1})").find("settings.sleep.time"), std::string::npos);
  EXPECT_NE(message(R"("sleep": {"sped": 0.1})").find("sped"), std::string::npos);
  EXPECT_NE(message(R"("sleep": true)").find("settings.sleep"), std::string::npos);
}

}  // namespace
}  // namespace moreau
