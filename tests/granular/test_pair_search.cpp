// The particle-contact pair search on the Morton-sorted cell grid (collision/particle_contacts.cpp)
// against every pair checked one by one: the same pairs, each once, for any thread count, with
// polydisperse radii, bonds of two reaches, and particles moving fast apart from the mean; and the
// tiles the pairs are solved in.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <set>
#include <vector>

#include "moreau/collision/particle_contacts.hpp"
#include "moreau/scene/scene.hpp"

namespace moreau {
namespace {

// Two granular objects (radii 2-5 mm; one cohesive with a 0.5 mm reach, the other with 1 mm), and
// a third dry one, scattered at random in a box 6 cm high and deep and `length` long; a quarter of
// them thrown at up to 20 m/s.
Scene scattered_grains(std::uint64_t seed, Real length = 0.06) {
  Scene scene = load_scene_text(R"({"name": "pairs", "settings": {"dt": 0.002, "duration": 1},
      "objects": [{"name": "a", "kind": "granular", "blocks": [{"min": [0, 0, 0], "max": [0.06, 0.06, 0.03]}],
                   "radius_range": [0.002, 0.005], "cohesion": 0.01, "cohesion_distance": 0.0005},
                  {"name": "b", "kind": "granular", "blocks": [{"min": [0, 0, 0.03], "max": [0.06, 0.06, 0.06]}],
                   "radius_range": [0.002, 0.005], "seed": 2, "cohesion": 0.02, "cohesion_distance": 0.001},
                  {"name": "c", "kind": "granular", "blocks": [{"min": [0, 0.06, 0], "max": [0.06, 0.08, 0.06]}],
                   "radius": 0.003}]})",
                                "pairs");
  std::mt19937_64 draw(seed);
  auto unit = [&] { return static_cast<Real>(draw() >> 11) * 0x1.0p-53; };
  for (Index p = 0; p < scene.model.particle_count(); ++p) {
    scene.state.position[p] = Vec3(length * unit(), 0.06 * unit(), 0.06 * unit());
    scene.state.velocity[p] = unit() < 0.25 ? Vec3(20 * (2 * unit() - 1), 20 * (2 * unit() - 1), 20 * (2 * unit() - 1))
                                            : Vec3(0.1 * unit(), 0, 0);
  }
  return scene;
}

// The pairs within reach r_i + r_j + g + min(k dt (|v_i - v_j| + dt |gravity|), r_i + r_j), checked one by one.
std::set<std::array<Index, 2>> every_pair_within_reach(const Model& m, const State& s) {
  std::set<std::array<Index, 2>> pairs;
  const Real k = m.settings.contact_margin_factor, dt = m.settings.dt;
  for (Index i = 0; i < m.particle_count(); ++i)
    for (Index j = i + 1; j < m.particle_count(); ++j) {
      const ObjectInfo &a = m.objects[m.particle_object[i]], &b = m.objects[m.particle_object[j]];
      const Real cohesion = 0.5 * (a.cohesion + b.cohesion);
      const Real bond = cohesion > 0 ? 0.5 * (a.cohesion_distance + b.cohesion_distance) : 0;
      const Real d = m.particle_radius[i] + m.particle_radius[j];
      const Real fall = dt * m.settings.gravity.norm();
      const Real reach = d + bond + std::min(k * dt * ((s.velocity[i] - s.velocity[j]).norm() + fall), d);
      if ((s.position[i] - s.position[j]).norm() < reach) pairs.insert({i, j});
    }
  return pairs;
}

TEST(PairSearch, FindsEveryPairWithinReachOnceForAnyThreadCount) {
  for (std::uint64_t seed : {1, 2, 3}) {
    Scene scene = scattered_grains(seed);
    const std::set<std::array<Index, 2>> expected = every_pair_within_reach(scene.model, scene.state);
    std::vector<std::array<Index, 2>> serial;
    for (int threads : {1, 2}) {
      ContactScratch scratch;
      detect_particle_contacts(scene.model, scene.state, scratch, threads);
      const std::vector<std::array<Index, 2>>& found = scene.state.particle_contacts.pair;
      const std::set<std::array<Index, 2>> unique(found.begin(), found.end());
      std::printf("seed %d, %d thread(s): %zu particles, %zu pairs found (%zu distinct), %zu within reach\n",
                  static_cast<int>(seed), threads, static_cast<size_t>(scene.model.particle_count()), found.size(),
                  unique.size(), expected.size());
      EXPECT_EQ(unique.size(), found.size()) << "a pair listed twice";
      EXPECT_TRUE(unique == expected);
      if (threads == 1) serial = found;
      else EXPECT_TRUE(found == serial) << "the order depends on the thread count";
    }
  }
}

// Grains (radii 2-5 mm, a bond of 1 mm reach) scattered at random in a 12 cm cube, three tiles
// along each axis; a quarter of them thrown at up to 20 m/s.
Scene grains_in_a_cube(std::uint64_t seed) {
  Scene scene = load_scene_text(R"({"name": "cube", "settings": {"dt": 0.002, "duration": 1},
      "objects": [{"name": "a", "kind": "granular", "blocks": [{"min": [0, 0, 0], "max": [0.12, 0.12, 0.12]}],
                   "radius_range": [0.002, 0.005], "cohesion": 0.02, "cohesion_distance": 0.001}]})",
                                "cube");
  std::mt19937_64 draw(seed);
  auto unit = [&] { return static_cast<Real>(draw() >> 11) * 0x1.0p-53; };
  for (Index p = 0; p < scene.model.particle_count(); ++p) {
    scene.state.position[p] = 0.12 * Vec3(unit(), unit(), unit());
    scene.state.velocity[p] = unit() < 0.25 ? Vec3(20 * (2 * unit() - 1), 20 * (2 * unit() - 1), 20 * (2 * unit() - 1))
                                            : Vec3(0.1 * unit(), 0, 0);
  }
  return scene;
}

// The tile batches (constraints/tile_batches.hpp) cover every pair once, the same for any thread
// count, and no particle is touched from two tiles of one colour (which run in parallel), with
// fast particles and bonds reaching farthest, in a long box (tiles of one colour apart along x)
// and in a cube (apart along any axis).
TEST(PairSearch, TilesOfOneColorTouchDisjointParticles) {
  for (std::uint64_t seed : {1, 2, 3}) {
    for (bool cube : {false, true}) {
      Scene scene = cube ? grains_in_a_cube(seed) : scattered_grains(seed, 0.3);  // about 6 tiles long
      ContactScratch scratch;
      detect_particle_contacts(scene.model, scene.state, scratch, 1);
      const ParticleContacts& c = scene.state.particle_contacts;
      const TileBatches& batches = c.batches;
      ASSERT_EQ(batches.color_count(), kTileColors);
      EXPECT_EQ(batches.tile_offsets.back(), static_cast<Index>(c.size())) << "the tiles do not cover the pairs";
      Index shared = 0, tiles = 0;
      for (Index color = 0; color < batches.color_count(); ++color) {
        std::vector<Index> owner(scene.model.particle_count(), -1);  // the tile of this colour that touches the particle
        for (Index t = batches.color_tiles[color]; t < batches.color_tiles[color + 1]; ++t, ++tiles)
          for (Index q = batches.tile_offsets[t]; q < batches.tile_offsets[t + 1]; ++q)
            for (Index p : c.pair[q]) {
              if (owner[p] >= 0 && owner[p] != t) ++shared;
              owner[p] = t;
            }
      }
      std::printf("seed %d, %s: %zu particles, %zu pairs in %d tiles of %d colours; %d particles touched from two tiles of one colour\n",
                  static_cast<int>(seed), cube ? "cube" : "long box", static_cast<size_t>(scene.model.particle_count()),
                  c.size(), static_cast<int>(tiles), kTileColors, static_cast<int>(shared));
      EXPECT_GT(tiles, kTileColors) << "too few tiles to test their separation";
      EXPECT_GT(c.size(), 0u);
      EXPECT_EQ(shared, 0);
      // Two threads: the same pairs in the same tiles.
      const std::vector<std::array<Index, 2>> serial = c.pair;
      const TileBatches serial_batches = batches;
      detect_particle_contacts(scene.model, scene.state, scratch, 2);
      EXPECT_TRUE(c.pair == serial);
      EXPECT_TRUE(batches.color_tiles == serial_batches.color_tiles);
      EXPECT_TRUE(batches.tile_offsets == serial_batches.tile_offsets);
    }
  }
}

}  // namespace
}  // namespace moreau
