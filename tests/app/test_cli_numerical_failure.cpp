// Numerical failure in every engine: a scene that blows up on purpose stops with exit code 3, a
// message naming the step, the time and the object, run.json with "status": "failed", and the
// frames and probe rows of the good steps before it, every file whole. One scene per engine and
// solver: xpbd, nmd and xpbi (particles driven past settings.max_speed by a huge gravity), FEM
// solids (a load that turns non-finite after 0.025 s) and a transient flow (a boundary velocity
// that does).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>

#include "scene_test_helpers.hpp"
#include "test_helpers.hpp"

namespace moreau {
namespace {

namespace fs = std::filesystem;

struct BlowUp {
  const char* name;
  std::string scene;
  std::vector<std::string> expected;  // what the message must name besides "step" and "t ="
};

// A cloth sheet pulled by 1e4 m/s^2: past max_speed = 100 m/s within the first steps.
std::string falling_cloth(const char* solver) {
  return fmt::format(R"({{"name": "boom", "settings": {{"solver": "{}", "dt": 0.02, "substeps": 1, "duration": 1,
    "max_speed": 100, "gravity": [0, -10000, 0]}},
    "objects": [{{"name": "sheet", "kind": "cloth", "mesh": {{"type": "grid", "size": [1, 1], "resolution": [4, 4]}},
      "material": {{"area_density": 0.1, "stretch_compliance": 0}}}}],
    "probes": [{{"name": "sheet", "type": "center_of_mass", "object": "sheet"}}]}})",
                     solver);
}

const BlowUp kBlowUps[] = {
    {"xpbd", falling_cloth("xpbd"), {"'sheet'"}},
    {"nmd", falling_cloth("nmd"), {"'sheet'"}},
    {"xpbi", R"({"name": "boom", "settings": {"solver": "xpbi", "dt": 0.02, "duration": 1, "max_speed": 100,
       "gravity": [0, -10000, 0]},
       "objects": [{"name": "dough", "kind": "continuum", "blocks": [{"min": [0, 0.5, 0], "max": [0.1, 0.6, 0.1]}],
         "spacing": 0.02, "density": 1000, "youngs_modulus": 1e5, "poisson_ratio": 0.3}],
       "probes": [{"name": "dough", "type": "center_of_mass", "object": "dough"}]})",
     {"'dough'"}},
    {"fem_solid", R"({"name": "boom", "settings": {"solver": "fem", "integrator": "midpoint", "dt": 0.01, "duration": 0.1,
       "gravity": [0, 0, 0]},
       "objects": [{"name": "bar", "kind": "solid", "mesh": {"type": "box", "min": [0, 0, 0], "max": [1, 0.1, 0.1], "cells": [4, 1, 1]},
         "material": {"youngs_modulus": 1e6, "poisson_ratio": 0.3, "density": 1000},
         "dirichlet": [{"where": {"boundary": "left"}, "value": [0, 0, 0]}],
         "loads": [{"type": "traction", "where": {"boundary": "right"}, "value": [0, "t > 0.025 ? 0/0 : 1000", 0]}]}],
       "probes": [{"name": "tip", "type": "point", "object": "bar", "nearest": [1, 0.05, 0.05]}]})",
     {"objects[0].loads[0].value[1]"}},
    {"flow", R"({"name": "boom", "settings": {"solver": "fem", "integrator": "bdf2", "dt": 0.01, "duration": 0.1, "gravity": [0, 0, 0]},
       "objects": [{"name": "fluid", "kind": "fluid", "mesh": {"type": "rectangle", "min": [0, 0], "max": [1, 1], "cells": [8, 8]},
         "density": 1.0, "viscosity": 0.01,
         "boundaries": [{"where": {"side": "top"}, "velocity": ["t > 0.025 ? 0/0 : 1", "0"]},
                        {"where": {"side": ["left", "right", "bottom"]}, "type": "no_slip"}],
         "pressure_reference": {"mean": 0}}],
       "probes": [{"name": "centre", "type": "point", "at": [0.5, 0.5]}]})",
     {"fluid"}},
};

class NumericalFailure : public ::testing::TestWithParam<BlowUp> {};

TEST_P(NumericalFailure, ExitsThreeNamingStepTimeAndObjectKeepingTheGoodSteps) {
  const BlowUp& c = GetParam();
  const std::string scene = test::write_scene(std::string("blowup-") + c.name, c.scene);
  const std::string out = fs::path(scene).parent_path() / "out";
  const test::CommandResult r = test::run_moreau(fmt::format("run {} --out {} --quiet", scene, out));
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_NE(r.output.find("numerical failure"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("step"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("t ="), std::string::npos) << r.output;
  for (const std::string& what : c.expected) EXPECT_NE(r.output.find(what), std::string::npos) << r.output;

  std::ifstream summary(out + "/run.json");
  ASSERT_TRUE(summary.good()) << r.output;
  const nlohmann::json run = nlohmann::json::parse(summary);
  EXPECT_EQ(run.at("status"), "failed");
  EXPECT_FALSE(run.at("message").get<std::string>().empty());
  // The good steps' samples stay: the one at t = 0 at least, every frame whole.
  EXPECT_GE(test::read_probes(out).size(), 1u);
  int frames = 0;
  for (const auto& f : fs::directory_iterator(out + "/frames")) {
    EXPECT_NE(f.path().extension(), ".part") << f.path();
    std::ifstream in(f.path(), std::ios::binary);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_NE(text.rfind("</VTKFile>"), std::string::npos) << f.path();
    ++frames;
  }
  EXPECT_GE(frames, 1);
}

INSTANTIATE_TEST_SUITE_P(Engines, NumericalFailure, ::testing::ValuesIn(kBlowUps),
                         [](const auto& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace moreau
