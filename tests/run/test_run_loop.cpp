// The one run loop steps every engine the same way: a run continues from the state that earlier
// World::step calls left, so stepping n times and running the rest gives bit for bit the
// probes of one run over the whole time, for the constraint engine, FEM solids with rigid bodies
// and joints, and a transient flow.
#include <gtest/gtest.h>

#include <filesystem>

#include "moreau/moreau.hpp"
#include "scene_test_helpers.hpp"

namespace moreau::test {
namespace {

namespace fs = std::filesystem;

struct Case {
  const char* name;
  const char* scene;  // a file in scenes/, or the scene's JSON
  std::vector<std::string> overrides;
  double dt;
  int steps;  // taken by World::step before the run of the rest
};

class RunLoopContinues : public ::testing::TestWithParam<Case> {};

TEST_P(RunLoopContinues, SteppingThenRunningEqualsOneRun) {
  const Case& c = GetParam();
  const double total = 2 * c.steps * c.dt;
  const std::string dir = temp_dir("run-loop");

  World whole = World::load(scene_path(c.scene), c.overrides);
  RunOptions options;
  options.out_dir = dir + "/whole";
  options.duration = total;
  whole.run(options);

  World parts = World::load(scene_path(c.scene), c.overrides);
  for (int s = 0; s < c.steps; ++s) parts.step();
  EXPECT_NEAR(parts.time(), c.steps * c.dt, 1e-12);
  options.out_dir = dir + "/parts";
  options.duration = total / 2;
  parts.run(options);

  EXPECT_EQ(whole.time(), parts.time());
  const auto a = read_probes(dir + "/whole"), b = read_probes(dir + "/parts");
  ASSERT_FALSE(a.empty());
  ASSERT_FALSE(b.empty());
  // The probe values (time column excluded) of the last sample: written with 17 digits, so equal
  // text means equal bits.
  ASSERT_EQ(a.back().size(), b.back().size());
  for (size_t k = 1; k < a.back().size(); ++k) EXPECT_EQ(a.back()[k], b.back()[k]) << c.name << " column " << k;
}

INSTANTIATE_TEST_SUITE_P(
    Engines, RunLoopContinues,
    ::testing::Values(Case{"Cloth", "tablecloth.json", {}, 1.0 / 60, 6},
                      Case{"SolidsBodiesJoints", "fem_hinged_beam.json", {}, 0.01, 5},
                      Case{"FreeSolid", "fem_flying_l.json", {}, 0.05, 3},
                      Case{"TransientFlow", kTransientCavity, {}, 0.05, 3}),
    [](const auto& info) { return std::string(info.param.name); });

// A steady flow is one solve: one probe row and one frame, of the solution (not of the start).
TEST(RunLoop, SteadyFlowWritesOnlyItsSolution) {
  const std::string dir = temp_dir("run-loop-steady");
  World sim = World::load(scene_path("cavity_re1000.json"),
                          {"objects.fluid.mesh.cells=[16,16]", "settings.newton.tolerance=1e-6"});
  RunOptions options;
  options.out_dir = dir;
  const RunResult r = sim.run(options);
  EXPECT_EQ(r.steps, 1);
  const auto rows = read_probes(dir);
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows[0][0], 0.0);
  // The lid drives the fluid: the centre moves (its velocity is nonzero), which the rest state does not.
  EXPECT_GT(std::abs(rows[0][1]) + std::abs(rows[0][2]), 1e-3);
  int frames = 0;
  for (const auto& f : fs::directory_iterator(dir + "/frames")) frames += f.path().extension() == ".vtu";
  EXPECT_EQ(frames, 1);
  EXPECT_TRUE(fs::exists(dir + "/line_vertical_centreline.csv"));
}

}  // namespace
}  // namespace moreau::test
