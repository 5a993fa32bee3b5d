// The public API (include/moreau/world.hpp): a World from a file or JSON text steps every engine,
// its state arrays are views of the state a step reads and writes, writing them steers the next
// step, its probes are the CLI's, and bad input is an InputError that says what there is.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>

#include "moreau/moreau.hpp"
#include "scene_test_helpers.hpp"

namespace moreau::test {
namespace {

std::string repository_scene(const char* name) {
  return (std::filesystem::path(MOREAU_SOURCE_DIR) / "scenes" / name).string();
}

// A box falling freely (no gravity: it keeps its velocity) and a cloth sheet beside it.
constexpr const char* kBoxAndSheet = R"({"name": "world", "settings": {"dt": 0.01, "gravity": [0, 0, 0]},
  "objects": [
    {"name": "box", "kind": "rigid_body", "shape": {"type": "box", "half_extents": [0.1, 0.1, 0.1]},
     "position": [0, 1, 0], "density": 500},
    {"name": "sheet", "kind": "cloth", "mesh": {"type": "grid", "size": [0.5, 0.5], "resolution": [4, 4],
     "center": [2, 1, 0]}, "material": {"area_density": 0.2}}],
  "probes": [{"name": "box_y", "type": "position", "object": "box"}]})";

TEST(World, StepsAndListsObjectsAndArraysOfTheConstraintEngine) {
  World world = World::from_json(kBoxAndSheet);
  EXPECT_EQ(world.name(), "world");
  EXPECT_EQ(world.engine(), "xpbd");
  const std::vector<WorldObject> objects = world.objects();
  ASSERT_EQ(objects.size(), 2u);
  EXPECT_EQ(objects[0].kind, "rigid_body");
  EXPECT_EQ(objects[0].count, 1);
  EXPECT_EQ(objects[1].kind, "cloth");
  EXPECT_EQ(objects[1].count, 16);

  const StateArray x = world.array("particle.position");
  EXPECT_EQ(x.components, 3);
  EXPECT_EQ(x.count, 16);
  EXPECT_EQ(x.values.size(), 48u);
  EXPECT_EQ(x.unit, "m");
  const StateArray q = world.array("body.orientation");
  EXPECT_EQ(q.components, 4);
  EXPECT_EQ(q.values[3], 1.0);  // x y z w of the identity

  // The sheet's corner is where the grid generator put it: centre (2, 1, 0), 0.5 m wide.
  EXPECT_DOUBLE_EQ(x.values[0], 2 - 0.25);
  world.step();
  world.step();
  EXPECT_EQ(world.steps(), 2);
  EXPECT_NEAR(world.time(), 0.02, 1e-15);
}

TEST(World, WrittenVelocitiesSteerTheNextStep) {
  // Without gravity or contacts a body keeps the velocity it is given: after one step of
  // dt = 0.01 s at (1, -2, 0.5) m/s it has moved by (0.01, -0.02, 0.005) m, to round-off.
  World world = World::from_json(kBoxAndSheet);
  StateArray v = world.array("body.velocity");
  ASSERT_TRUE(v.writable);
  v.values[0] = 1;
  v.values[1] = -2;
  v.values[2] = 0.5;
  world.step();
  const StateArray x = world.array("body.position");
  EXPECT_NEAR(x.values[0], 0.01, 1e-15);
  EXPECT_NEAR(x.values[1], 1 - 0.02, 1e-15);
  EXPECT_NEAR(x.values[2], 0.005, 1e-15);
  EXPECT_EQ(world.probe_names(), (std::vector<std::string>{"box_y.x", "box_y.y", "box_y.z"}));
  EXPECT_EQ(world.probe_values()[1], x.values[1]);
}

TEST(World, StepsThenProbesExactlyAsTheCommandLineRun) {
  // 30 steps of the tablecloth through World::step, and the CLI's run of the same 0.5 s: the
  // probes.csv row is written with 17 significant digits, so equal values mean equal bits.
  const std::string scene = repository_scene("tablecloth.json");
  World world = World::load(scene);
  for (int s = 0; s < 30; ++s) world.step();
  const auto rows = run_scene(scene, temp_dir("world-cli") + "/out", fmt::format("--duration {}", world.time()));
  ASSERT_FALSE(rows.empty());
  const std::vector<double> values = world.probe_values();
  ASSERT_EQ(rows.back().size(), values.size() + 1);
  EXPECT_NEAR(rows.back()[0], world.time(), 1e-12);  // the time column is rounded for reading
  for (size_t k = 0; k < values.size(); ++k) EXPECT_EQ(rows.back()[k + 1], values[k]) << world.probe_names()[k];
}

TEST(World, OffersTheFemAndFlowEnginesFields) {
  World solids = World::load(repository_scene("fem_hinged_beam.json"));
  EXPECT_EQ(solids.engine(), "fem");
  const StateArray u = solids.array("solid.displacement");
  EXPECT_EQ(u.components, 3);
  long nodes = 0;
  for (const WorldObject& o : solids.objects()) nodes += o.kind == "solid" ? o.count : 0;
  EXPECT_EQ(u.count, nodes);
  EXPECT_EQ(solids.array("body.director_state").components, 24);
  solids.step();
  EXPECT_GT(solids.stage_times().at("solve"), 0);

  World flow = World::load(repository_scene("cavity_re1000.json"), {"objects.fluid.mesh.cells=[8,8]"});
  EXPECT_EQ(flow.engine(), "flow");
  const StateArray solution = flow.array("flow.solution");
  EXPECT_EQ(solution.components, 3);  // u, v, p in 2D
  EXPECT_EQ(solution.count, 81);
}

TEST(World, BadInputSaysWhereAndWhatThereIs) {
  try {
    World::from_json(R"({"name": "bad", "objects": [{"name": "a", "kind": "cloud"}]})");
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::strstr(e.what(), "(scene JSON)"), nullptr) << e.what();
    EXPECT_NE(std::strstr(e.what(), "objects[0].kind"), nullptr) << e.what();
  }
  World world = World::from_json(kBoxAndSheet);
  try {
    world.array("particle.colour");
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::strstr(e.what(), "particle.velocity"), nullptr) << e.what();
  }
}

TEST(World, StageTimesNameTheSolversStages) {
  World world = World::from_json(kBoxAndSheet);
  world.step();
  const std::map<std::string, double> times = world.stage_times();
  EXPECT_TRUE(times.count("predict"));
  EXPECT_TRUE(times.count("rigid_contacts"));
  double total = 0;
  for (const auto& [stage, seconds] : times) total += seconds;
  EXPECT_GT(total, 0);
}

}  // namespace
}  // namespace moreau::test
