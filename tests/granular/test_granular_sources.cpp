// Where a granular object's grains come from: a closed mesh fills as the block it bounds, and
// an emitter's scene keys are checked with their paths.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <fstream>
#include <string>
#include <vector>

#include "moreau/world.hpp"
#include "test_helpers.hpp"

namespace moreau {
namespace {

// The cube [0, 0.1]^3 as a closed OBJ surface of 12 outward triangles.
std::string write_cube(const std::string& dir) {
  const std::string path = dir + "/cube.obj";
  std::ofstream out(path);
  for (int i = 0; i < 8; ++i) out << fmt::format("v {} {} {}\n", 0.1 * (i & 1), 0.1 * ((i >> 1) & 1), 0.1 * ((i >> 2) & 1));
  // Vertex i + 1 sits at (i & 1, i & 2, i & 4); two triangles per face.
  out << "f 1 3 2\nf 2 3 4\nf 5 6 7\nf 6 8 7\nf 1 2 5\nf 2 6 5\nf 3 7 4\nf 4 7 8\nf 1 5 3\nf 3 5 7\nf 2 4 6\nf 4 8 6\n";
  return path;
}

std::vector<double> grain_positions(const std::string& source) {
  World w = World::from_json(fmt::format(R"({{"name": "fill", "settings": {{"dt": 0.001, "duration": 1}},
      "objects": [{{"name": "sand", "kind": "granular", {}, "radius_range": [0.004, 0.005]}}]}})", source));
  const StateArray x = w.array("particle.position");
  return {x.values.begin(), x.values.end()};
}

// Every lattice point of the cube's bounding box lies inside it, so the mesh holds the grains of
// the block [0, 0.1]^3, with the same draws: the same positions, bit for bit (9^3 = 729 grains).
TEST(GranularSources, AClosedMeshFillsLikeTheBlockItBounds) {
  const std::string cube = write_cube(test::temp_dir("granular-mesh"));
  const std::vector<double> from_mesh = grain_positions(fmt::format(R"("mesh": "{}")", cube));
  const std::vector<double> from_block = grain_positions(R"("blocks": [{"min": [0, 0, 0], "max": [0.1, 0.1, 0.1]}])");
  EXPECT_EQ(from_mesh.size(), 3u * 729);
  EXPECT_EQ(from_mesh, from_block);
}

// The corner tetrahedron x + y + z <= 0.1 of that cube keeps only the lattice points inside it:
// as many grains as the points (r_max + i d, r_max + j d, r_max + k d), d = 2.04 r_max, with
// x + y + z < 0.1, and every grain centre within its lattice jitter (1 % of r) of the inside.
TEST(GranularSources, AClosedMeshKeepsOnlyTheLatticePointsInsideIt) {
  const std::string path = test::temp_dir("granular-mesh") + "/corner.obj";
  {
    std::ofstream out(path);
    out << "v 0 0 0\nv 0.1 0 0\nv 0 0.1 0\nv 0 0 0.1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
  }
  const std::vector<double> x = grain_positions(fmt::format(R"("mesh": "{}")", path));
  const Real r = 0.005, d = 2.04 * r;
  long inside = 0;
  for (int i = 0; i < 9; ++i)  // the box holds 9 points a side: (0.1 - 2 r) / d + 1 = 9.8
    for (int j = 0; j < 9; ++j)
      for (int k = 0; k < 9; ++k) inside += 3 * r + d * (i + j + k) < 0.1;
  Real outside = 0;  // m: the furthest a centre lies beyond the slanted face
  for (size_t p = 0; p < x.size(); p += 3) outside = std::max(outside, (x[p] + x[p + 1] + x[p + 2] - 0.1) / std::sqrt(3.0));
  std::printf("corner tetrahedron: %zu grains (lattice points inside: %ld), furthest %.2g m beyond its face\n",
              x.size() / 3, inside, outside);
  EXPECT_EQ(static_cast<long>(x.size() / 3), inside);
  EXPECT_GT(inside, 10);
  EXPECT_LT(inside, 729);
  EXPECT_LE(outside, 0.01 * r * std::sqrt(3.0));
}

// Bad emitter keys fail with the key's path and what is allowed.
TEST(GranularSources, EmitterKeysAreChecked) {
  struct Case {
    std::string emitter, path, message;
  };
  const std::vector<Case> cases{
      {R"("shape": "disc", "center": [0, 1, 0], "direction": [0, -1, 0], "radius": 0.03, "speed": 1, "mass_rate": 1)",
       "objects[0].emitter.speed", "exactly one of"},
      {R"("shape": "disc", "center": [0, 1, 0], "direction": [0, -1, 0], "radius": 0.03, "flow_rate": 1)",
       "objects[0].emitter.flow_rate", "grains are poured at a \"mass_rate\""},
      {R"("shape": "disc", "center": [0, 1, 0], "direction": [0, 0, 0], "radius": 0.03, "speed": 1)",
       "objects[0].emitter.direction", "non-zero"},
      {R"("shape": "disc", "center": [0, 1, 0], "direction": [0, -1, 0], "radius": 0.001, "speed": 1)",
       "objects[0].emitter.radius", "grain spacing"},
      {R"("shape": "disc", "center": [0, 1, 0], "direction": [0, -1, 0], "radius": 0.03, "speed": 1e6)",
       "objects[0].emitter.stop", "limit"},
  };
  for (const Case& c : cases) {
    try {
      World::from_json(fmt::format(R"({{"name": "bad", "settings": {{"dt": 0.001, "duration": 10}},
          "objects": [{{"name": "sand", "kind": "granular", "radius": 0.005, "emitter": {{{}}}}}]}})", c.emitter));
      ADD_FAILURE() << "no error for " << c.emitter;
    } catch (const std::exception& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(c.path), std::string::npos) << what;
      EXPECT_NE(what.find(c.message), std::string::npos) << what;
    }
  }
}

// A joint or a point probe cannot take a grain an emitter has yet to release: an object whose
// grains all come from an emitter is refused at the end's or probe's "object", and `nearest`
// picks among the grains there from the start.
TEST(GranularSources, EmittedGrainsHoldNoJointOrProbe) {
  const std::string emitter = R"("emitter": {"shape": "disc", "center": [0, 1, 0], "direction": [0, -1, 0], "radius": 0.03, "speed": 1})";
  auto error = [&](const std::string& source, const std::string& extra) {
    try {
      World::from_json(fmt::format(R"({{"name": "bad", "settings": {{"dt": 0.001, "duration": 1}},
          "objects": [{{"name": "sand", "kind": "granular", "radius": 0.005, {}}}], {}}})", source, extra));
    } catch (const std::exception& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::string probe = R"("probes": [{"name": "p", "type": "point", "object": "sand", "nearest": [0, 1, 0]}])";
  const std::string joint = R"("joints": [{"name": "j", "type": "spherical", "bodies": ["world", {"object": "sand", "nearest": [0, 1, 0]}], "anchor": [0, 1, 0]}])";
  EXPECT_NE(error(emitter, probe).find("probes[0].object"), std::string::npos) << error(emitter, probe);
  EXPECT_NE(error(emitter, joint).find("joints[0]"), std::string::npos) << error(emitter, joint);
  // With a block too, `nearest` [0, 1, 0] (the opening) picks a block grain; the last block grain is the highest vertex.
  const std::string both = R"("blocks": [{"min": [0, 0, 0], "max": [0.0102, 0.0204, 0.0102]}], )" + emitter;
  World w = World::from_json(fmt::format(R"({{"name": "ok", "settings": {{"dt": 0.001, "duration": 1}},
      "objects": [{{"name": "sand", "kind": "granular", "radius": 0.005, {}}}], {}}})", both, probe));
  // The upper block grain's height, r + d = 0.0152 m, not the opening's 1 m, within its lattice jitter (1 % of r).
  EXPECT_NEAR(w.probe_values().at(1), 0.005 + 2.04 * 0.005, 0.01 * 0.005);
  EXPECT_NE(error(both, R"("probes": [{"name": "p", "type": "point", "object": "sand", "vertex": 2}])").find("probes[0].vertex"),
            std::string::npos);
}

}  // namespace
}  // namespace moreau
