// Grain emitters: layers released on time at the mass rate, each grain on its exact free fall
// from the moment it is due; a covered opening waits; the unreleased grains are not written;
// the same grains on one and two threads.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "moreau/math/types.hpp"
#include "moreau/world.hpp"
#include "test_helpers.hpp"

namespace moreau {
namespace {

constexpr Real kRadius = 0.005, kSpacing = 2 * kRadius * 1.02;  // the granular lattice's spacing
const Real kGrainMass = 2600 * 4 * kPi / 3 * kRadius * kRadius * kRadius;

// A disc of radius 0.03 m on the 10.2 mm lattice holds the points (i, j) d with |(i, j)| d <= 0.03:
// i, j in -2..2, 25 of them (the corners lie 28.8 mm out).
constexpr int kDiscGrains = 25;

std::string pour_scene(const std::string& emitter, const std::string& extra_settings = "") {
  return fmt::format(
      R"({{"name": "pour", "settings": {{"dt": 0.005, "substeps": 10, "duration": 1{}}},
      "objects": [{{"name": "ground", "kind": "collider", "shape": {{"type": "plane"}}}},
                  {{"name": "sand", "kind": "granular", "radius": 0.005, "emitter": {}}}],
      "probes": [{{"name": "grains", "type": "particle_count", "object": "sand"}}]}})",
      extra_settings, emitter);
}

Real live_grains(const World& w) { return w.probe_values().at(0); }

// Grains released from a disc 1 m up from t = 0.0123 s to 0.3 s, at 0.5 kg/s: v = rate d / (N m)
// = 0.1499 m/s, a layer every d / v = 68.1 ms. After each step the live grains number N (k + 1),
// k the last layer due by the step's start (layers are released at the start of a step). Each
// grain then falls freely: released at the step's start t_s at x_k + v (t_s - t_k) along the
// flow, with velocity v, and moved by n substeps of the symplectic Euler step, which puts it at
// y_s - v n h - g h^2 n (n + 1) / 2: its height less that stays its lattice offset (at most 1 %
// of r) to rounding (1e-10 m) as it falls.
TEST(GrainEmitter, ReleasesItsLayersOnTimeAndEachGrainFallsFromItsDueTime) {
  const Real start = 0.0123, stop = 0.3, rate = 0.5, h = 0.005 / 10, g = 9.81, y0 = 1;
  World w = World::from_json(pour_scene(fmt::format(R"({{"shape": "disc", "center": [0, {}, 0], "direction": [0, -1, 0],
      "radius": 0.03, "mass_rate": {}, "start": {}, "stop": {}}})", y0, rate, start, stop)));
  const WorldObject sand = w.objects().at(1);
  const Real v = rate * kSpacing / (kDiscGrains * kGrainMass);
  const int layers = static_cast<int>(std::floor((stop - start) * v / kSpacing + 1e-9)) + 1;
  ASSERT_EQ(sand.count, layers * kDiscGrains) << "every grain the emitter will release exists from the start";

  std::vector<Real> released_at(layers, -1);       // the start of the step that released each layer
  std::vector<Real> offset(sand.count, 0);          // m, each grain's height less its free fall
  StateArray x = w.array("particle.position");
  Real worst_drift = 0, worst_offset = 0;
  while (w.time() < 0.35 - 1e-9) {  // the first layer falls 0.62 m by then: no grain reaches the ground
    const Real step_start = w.time();
    w.step();
    const int due = step_start >= start
                        ? std::min(layers, static_cast<int>(std::floor((step_start - start) * v / kSpacing + 1e-9)) + 1)
                        : 0;
    ASSERT_EQ(live_grains(w), due * kDiscGrains) << "t = " << step_start;
    for (int k = 0; k < due; ++k) {
      const bool new_layer = released_at[k] < 0;
      if (new_layer) released_at[k] = step_start;
      const Real due_time = start + k * kSpacing / v;
      const long n = std::lround((w.time() - released_at[k]) / h);
      const Real fall = (y0 - v * (released_at[k] - due_time)) - v * n * h - g * h * h * n * (n + 1) / 2;
      for (int i = 0; i < kDiscGrains; ++i) {
        const long p = sand.first + k * kDiscGrains + i;
        const Real off = x.values[3 * p + 1] - fall;
        if (new_layer) offset[p - sand.first] = off;
        worst_offset = std::max(worst_offset, std::abs(off));
        worst_drift = std::max(worst_drift, std::abs(off - offset[p - sand.first]));
      }
    }
  }
  std::printf("grain emitter: %d layers of %d grains at v = %.4f m/s, released on time; heights off their free fall by "
              "at most %.3g m (lattice offsets), drifting %.3g m\n",
              layers, kDiscGrains, v, worst_offset, worst_drift);
  EXPECT_LE(worst_offset, 0.01 * kRadius * (1 + 1e-9));
  EXPECT_LT(worst_drift, 1e-10);  // rounding of 700 substeps of v = (x - x_start) / h at 1 m
}

// Grains of radii drawn in [4, 5] mm poured at 0.5 kg/s for 0.5 s: the emitter sets its speed from
// the expected grain mass rho 4/3 pi E[r^3], and the mass measured through a plane below the
// opening once every grain has passed (the `mass_flow` probe's `beyond`) is the rate times the
// window, 0.25 kg, to within one layer (25 grains of 1.0 g: the window's end cuts the last layer)
// plus three standard deviations of the drawn masses (a grain's mass scatters by 19 % about the
// mean, about 250 grains: 1.2 %, 9 g). Sizing the speed by the largest grain would pour 26 % less.
TEST(GrainEmitter, PoursItsMassRateWithGrainsOfDrawnRadii) {
  const Real rate = 0.5, window = 0.5;
  World w = World::from_json(R"({"name": "pour", "settings": {"dt": 0.005, "substeps": 10, "duration": 1},
      "objects": [{"name": "sand", "kind": "granular", "radius_range": [0.004, 0.005],
                   "emitter": {"shape": "disc", "center": [0, 1, 0], "direction": [0, -1, 0], "radius": 0.03,
                               "mass_rate": 0.5, "start": 0, "stop": 0.5}}],
      "probes": [{"name": "poured", "type": "mass_flow", "object": "sand", "point": [0, 0.9, 0], "normal": [0, -1, 0],
                  "quantity": "beyond"}]})");
  while (w.time() < 0.75 - 1e-9) w.step();  // the last layer (due by 0.5 s) has passed y = 0.9 m by 0.65 s
  const Real poured = w.probe_values().at(0);
  const Real mean_cube = (std::pow(0.005, 4) - std::pow(0.004, 4)) / (4 * 0.001);
  const Real layer = kDiscGrains * 2600 * 4 * kPi / 3 * mean_cube;
  std::printf("grain emitter with radii in [4, 5] mm: poured %.4f kg through the plane, the rate's %.4f kg\n", poured,
              rate * window);
  EXPECT_NEAR(poured, rate * window, layer + 0.009);
}

// The deepest overlap of any two of the first `count` grains (from `first`), m.
Real deepest_overlap(const StateArray& x, long first, long count) {
  Real deepest = 0;
  for (long i = first; i < first + count; ++i)
    for (long j = i + 1; j < first + count; ++j) {
      const Real dx = x.values[3 * i] - x.values[3 * j], dy = x.values[3 * i + 1] - x.values[3 * j + 1],
                 dz = x.values[3 * i + 2] - x.values[3 * j + 2];
      deepest = std::max(deepest, 2 * kRadius - std::sqrt(dx * dx + dy * dy + dz * dz));
    }
  return deepest;
}

// A spout 3 cm above the ground pours 2 kg/s: the grains pile up to it, and the emitter waits
// while grains lie where its next layer would appear. It stops pouring (the count stays put
// over the last half second), the pile comes to rest (every grain slower than 5 cm/s), and no
// layer was released into grains: the deepest overlap stays what resting grains keep (below 5 %
// of r). Released regardless, the layers land in the pile and the contacts throw grains out at
// 1.9 m/s, and all 1475 grains are poured.
TEST(GrainEmitter, WaitsWhileGrainsCoverItsOpening) {
  World w = World::from_json(pour_scene(R"({"shape": "disc", "center": [0, 0.03, 0], "direction": [0, -1, 0],
      "radius": 0.03, "mass_rate": 2})"));
  const WorldObject sand = w.objects().at(1);
  while (w.time() < 0.5 - 1e-9) w.step();
  const Real count_at_half = live_grains(w);
  while (w.time() < 1 - 1e-9) w.step();
  const Real count = live_grains(w);
  StateArray x = w.array("particle.position"), v = w.array("particle.velocity");
  Real fastest = 0;
  for (long p = sand.first; p < sand.first + static_cast<long>(count); ++p)
    fastest = std::max(fastest, std::hypot(v.values[3 * p], v.values[3 * p + 1], v.values[3 * p + 2]));
  const Real overlap = deepest_overlap(x, sand.first, static_cast<long>(count));
  std::printf("covered spout: %g of %ld grains released (%g at 0.5 s); fastest grain %.3g m/s; deepest overlap %.3g mm\n",
              count, sand.count, count_at_half, fastest, 1e3 * overlap);
  EXPECT_EQ(count, count_at_half);
  EXPECT_LT(count, sand.count);
  EXPECT_LT(fastest, 0.05);
  EXPECT_LT(overlap, 0.05 * kRadius);
}

// The frames hold the released grains only: none at t = 0 (the emitter starts at 0.05 s), one
// layer's 25 after the first output step past it.
TEST(GrainEmitter, FramesHoldOnlyReleasedGrains) {
  const std::string out = test::temp_dir("grain-emitter-output");
  World w = World::from_json(pour_scene(R"({"shape": "disc", "center": [0, 0.5, 0], "direction": [0, -1, 0],
      "radius": 0.03, "speed": 0.5, "start": 0.05, "stop": 0.06})", R"(, "output": {"every": 12})"));
  RunOptions options;
  options.out_dir = out;
  options.duration = 0.12;
  w.run(options);
  auto points = [&](int frame) {
    std::ifstream in(fmt::format("{}/frames/sand_{:06d}.vtp", out, frame));
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const size_t at = text.find("NumberOfPoints=\"");
    return at == std::string::npos ? -1 : std::stoi(text.substr(at + 16));
  };
  EXPECT_EQ(points(0), 0);             // t = 0
  EXPECT_EQ(points(1), kDiscGrains);   // t = 0.06: the layer due at 0.05 s
  EXPECT_EQ(points(2), kDiscGrains);   // t = 0.12: the window closed after one layer (0.01 s < d / v)
}

// Grains poured onto the ground come out bit-identical on one and two threads, under xpbd and
// nmd.
TEST(GrainEmitter, SameGrainsOnOneAndTwoThreads) {
  for (const std::string solver : {"", R"(, "solver": "nmd")"}) {
    std::vector<std::vector<double>> runs;
    for (int threads : {1, 2}) {
      World w = World::from_json(pour_scene(R"({"shape": "rectangle", "center": [0, 0.15, 0], "direction": [0, -1, 0],
          "size": [0.06, 0.04], "speed": 0.5})", solver));
      while (w.time() < 0.3 - 1e-9) w.step(threads);
      const StateArray x = w.array("particle.position");
      runs.emplace_back(x.values.begin(), x.values.end());
    }
    EXPECT_EQ(runs[0], runs[1]) << solver;
  }
}

}  // namespace
}  // namespace moreau
