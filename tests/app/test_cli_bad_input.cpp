// The command line's answers to bad input (exit 2, naming the problem, nothing written) and to
// numerical failure (exit 3, naming the step, the time and the culprit), for inputs a new user
// tried: out-of-range flags, non-finite numbers, duplicate keys, directories and unwritable
// output places, a non-finite load.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "scene_test_helpers.hpp"
#include "test_helpers.hpp"

namespace moreau {
namespace {

namespace fs = std::filesystem;

const std::string kShowcase = std::string(MOREAU_SOURCE_DIR) + "/scenes/showcase.json";

void expect_bad_input(const std::string& args, const std::string& message) {
  const test::CommandResult r = test::run_moreau(args);
  EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.output;
  EXPECT_NE(r.output.find(message), std::string::npos) << args << "\n" << r.output;
  EXPECT_EQ(r.output.find("internal error"), std::string::npos) << args << "\n" << r.output;
}

TEST(CliBadInput, FlagsOutOfRangeAreRefused) {
  const std::string out = test::temp_dir("flags") + "/out";
  // --threads 100000 crashed in libgomp and 30000 hung; the scene key has the same limit.
  expect_bad_input(fmt::format("run {} --out {} --threads 100000", kShowcase, out), "not in range 0 to 1024");
  expect_bad_input(fmt::format("run {} --out {} --threads 30000", kShowcase, out), "not in range 0 to 1024");
  // --duration nan was ignored silently.
  expect_bad_input(fmt::format("run {} --out {} --duration nan", kShowcase, out), "must be a finite time > 0 s");
  expect_bad_input(fmt::format("run {} --out {} --duration inf", kShowcase, out), "must be a finite time > 0 s");
  EXPECT_FALSE(fs::exists(out));
}

TEST(CliBadInput, NumbersThatOverflowADoubleAreBadInput) {
  const std::string dir = test::temp_dir("overflow");
  std::ofstream(dir + "/big.json") << R"({"name": "big", "settings": {"dt": 1e999}})";
  expect_bad_input(fmt::format("check {}/big.json", dir), "settings.dt: the number '1e999' does not fit a double");
  expect_bad_input(fmt::format("check {} --set settings.dt=1e999", kShowcase), "does not fit a double");
}

TEST(CliBadInput, DuplicateKeysAreRefusedWithTheirPath) {
  const std::string dir = test::temp_dir("duplicate");
  std::ofstream(dir + "/dup.json") << R"({"name": "dup", "objects": [{"name": "a", "kind": "collider"},
    {"name": "b", "kind": "collider", "shape": {"type": "plane", "type": "box"}}]})";
  expect_bad_input(fmt::format("check {}/dup.json", dir), "objects[1].shape.type: the key appears twice");
}

TEST(CliBadInput, WhatIsNotASceneFileIsNamed) {
  const std::string dir = test::temp_dir("notscene");
  expect_bad_input(fmt::format("check {}", dir), "is a directory");
  std::ofstream(dir + "/nul.json") << std::string("{\"name\": \"x\"\0}", 14);
  expect_bad_input(fmt::format("check {}/nul.json", dir), "NUL byte");
  // A mesh file that is a directory was reported as "OBJ file has no faces".
  fs::create_directories(dir + "/meshes");
  std::ofstream(dir + "/hull.json") << R"({"name": "hull", "objects": [{"name": "rock", "kind": "rigid_body",
    "shape": {"type": "convex_hull", "mesh": "meshes"}, "position": [0, 1, 0]}]})";
  expect_bad_input(fmt::format("check {}/hull.json", dir), "is a directory; give the path of a mesh file");
}

TEST(CliBadInput, AMisspeltKeyIsNamedBeforeTheKeyItWasMeantToBe) {
  // Each was reported as the required key being missing ("shape.center: missing required key").
  const std::string dir = test::temp_dir("misspelt");
  const std::string body = R"({"name": "b", "kind": "cloth", "mesh": {"type": "grid", "size": [1, 1], "resolution": [2, 2]},
                               "material": {"area_density": 0.1}})";
  auto scene = [&](const std::string& tag, const std::string& objects, const std::string& probes) {
    const std::string path = fmt::format("{}/{}.json", dir, tag);
    std::ofstream(path) << fmt::format(R"({{"name": "{}", "objects": [{}], "probes": [{}]}})", tag, objects, probes);
    return "check " + path;
  };
  expect_bad_input(scene("box", R"({"name": "floor", "kind": "collider", "shape": {"type": "box", "min": [0, 0, 0], "max": [1, 1, 1]}})", ""),
                   "objects[0].shape.max: unknown key (did you mean 'center', which is required here?); allowed here: type, center, half_extents, size, rotation_deg");
  expect_bad_input(scene("capsule", R"({"name": "c", "kind": "rigid_body", "density": 1000, "position": [0, 1, 0],
                                        "shape": {"type": "capsule", "radius": 0.1, "half_length": 0.2}})", ""),
                   "objects[0].shape.half_length: unknown key (did you mean 'half_height', which is required here?)");
  expect_bad_input(scene("reduce", body, R"({"name": "top", "type": "extent", "object": "b", "axis": "y", "reduce": "max"})"),
                   "probes[0].reduce: unknown key (did you mean 'quantity', which is required here?)");
  // With no declared list, a near-spelling of the missing key, and the closest key for a typo of
  // an optional one.
  expect_bad_input(scene("radius", R"({"name": "s", "kind": "rigid_body", "density": 1000, "position": [0, 1, 0],
                                       "shape": {"type": "sphere", "raduis": 0.1}})", ""),
                   "objects[0].shape.raduis: unknown key (did you mean 'radius', which is required here?)");
  // A correct key beside the missing one is not called unknown (min and max are two letters apart).
  expect_bad_input(scene("sibling", R"({"name": "floor", "kind": "collider", "shape": {"type": "box", "size": [1, 1, 1]}})", ""),
                   "objects[0].shape.center: missing required key");
  {
    const std::string path = dir + "/min.json";
    std::ofstream(path) << R"({"name": "min", "objects": [{"name": "b", "kind": "soft_body",
      "mesh": {"type": "box", "max": [1, 1, 1], "cells": [2, 2, 2]},
      "material": {"youngs_modulus": 1e5, "poisson_ratio": 0.3, "density": 1000}}]})";
    expect_bad_input("check " + path, "objects[0].mesh.min: missing required key");
  }
  expect_bad_input(scene("optional", body, R"({"name": "top", "type": "extent", "object": "b", "axis": "y", "quantity": "max", "objcet": 1})"),
                   "probes[0].objcet: unknown key (did you mean 'object'?)");
  expect_bad_input(fmt::format("check {} --set settings.substep=4", kShowcase), "settings.substep: unknown key (did you mean 'substeps'?)");
}

TEST(CliBadInput, FemEnergyAndMomentumProbesAreOfTheWholeModel) {
  // They measure the whole model; an "object" key was accepted with any value. As in constraint-
  // engine scenes, "*" names the whole model; any other object is refused.
  const std::string dir = test::temp_dir("femprobe");
  std::ofstream(dir + "/beam.json") << R"({"name": "beam",
    "settings": {"solver": "fem", "dt": 0.01, "duration": 0.02, "integrator": "midpoint", "gravity": [0, 0, 0]},
    "objects": [{"name": "beam", "kind": "solid", "mesh": {"type": "box", "min": [0, 0, 0], "max": [1, 0.1, 0.1], "cells": [4, 1, 1], "element": "hex8"},
                "material": {"youngs_modulus": 1e6, "poisson_ratio": 0.3, "density": 1000}}],
    "probes": [{"name": "E", "type": "energy", "object": "nothing"}]})";
  expect_bad_input(fmt::format("check {}/beam.json", dir), "probes[0].object: energy and momentum are of the whole model");
}

TEST(CliBadInput, FemAndFlowSettingsOfferOnlyTheirOwnKeys) {
  // XPBD's substeps, iterations, particle_contacts, ... were accepted (and ignored) in FEM and
  // flow scenes, and offered in their lists of allowed keys.
  const std::string allowed = "allowed here: dt, duration, gravity, integrator, linear_solver, newton, output, solver, threads";
  const std::string scenes = std::string(MOREAU_SOURCE_DIR) + "/scenes/";
  expect_bad_input(fmt::format("check {}cavity_re1000.json --set settings.substeps=4", scenes), "settings.substeps: unknown key; " + allowed);
  expect_bad_input(fmt::format("check {}fem_beam.json --set settings.particle_contacts=false", scenes),
                   "settings.particle_contacts: unknown key; " + allowed);
}

TEST(CliBadInput, ScenesTooLargeForMemoryAreRefusedBeforeAllocating) {
  // cells [100000, 100000] failed at once with bad_alloc (exit 1); a 2000^3 soft body grew to
  // 3 GB first. The estimate (count x a measured lower bound per item) is checked before any
  // allocation; the limit is 80 % of physical memory, or --memory-limit.
  const std::string dir = test::temp_dir("memory");
  std::ofstream(dir + "/soft.json") << R"({"name": "soft", "objects": [{"name": "b", "kind": "soft_body",
    "mesh": {"type": "box", "min": [0, 0, 0], "max": [1, 1, 1], "cells": [2000, 2000, 2000]},
    "material": {"youngs_modulus": 1e5, "poisson_ratio": 0.3, "density": 1000}}]})";
  expect_bad_input(fmt::format("check {}/soft.json", dir), "objects[0].mesh.cells: 4.8e+10 tetrahedra need at least 1.44e+04 GB");
  expect_bad_input(fmt::format("check {}/soft.json", dir), "raise the limit with --memory-limit <GB>");
  const std::string scenes = std::string(MOREAU_SOURCE_DIR) + "/scenes/";
  expect_bad_input(fmt::format("check {}cavity_re1000.json --set objects.fluid.mesh.cells=[100000,100000]", scenes),
                   "objects[0].mesh.cells: 1e+10 cells need at least 6e+04 GB");
  expect_bad_input(fmt::format("check {}fem_beam.json --set objects.beam.mesh.cells=[100000,100000,2]", scenes),
                   "objects[0].mesh.cells: 2e+10 cells need at least 2e+05 GB");
  // A fluid tank's walls are sampled at the fluid's spacing: a tank 2 km square at 2.5 cm is
  // 1.3e10 wall samples, refused at the tank's shape before any is made.
  expect_bad_input(fmt::format("check {}dam_break.json --set objects.tank.shape.half_extents=[1000,0.5,1000]", scenes),
                   "objects[0].shape: ");
  expect_bad_input(fmt::format("check {}dam_break.json --set objects.tank.shape.half_extents=[1000,0.5,1000]", scenes),
                   "fluid wall samples at the fluid's particle spacing need at least");
  // A small scene under a smaller limit given on the command line.
  const std::string small = fmt::format("{}/soft.json --set objects.b.mesh.cells=[40,40,40]", dir);
  expect_bad_input(fmt::format("check {} --memory-limit 0.1", small),
                   "3.84e+05 tetrahedra need at least 0.115 GB (300 bytes each), more than the memory limit of 0.1 GB (set by --memory-limit)");
  EXPECT_EQ(test::run_moreau(fmt::format("check {} --memory-limit 1", small)).exit_code, 0);
}

TEST(CliBadInput, FemScenesWriteVtkFramesOnly) {
  const std::string scenes = std::string(MOREAU_SOURCE_DIR) + "/scenes/";
  expect_bad_input(fmt::format("check {}fem_beam.json --set 'settings.output.formats=[\"obj\"]'", scenes),
                   "settings.output.formats: \"obj\" is not a known format; allowed: vtk (FEM scenes)");
}

TEST(CliBadInput, RunsThatCannotFinishOrFitOnDiskAreRefused) {
  // --duration 1e12 wrote frames without end (125 MB in 20 s); 1e300 overflowed the step count
  // and ran one step. The output is projected from the first frame against the free space.
  const std::string out = test::temp_dir("endless") + "/out";
  expect_bad_input(fmt::format("run {} --out {} --quiet --duration 1e12", kShowcase, out),
                   "the run would write");
  expect_bad_input(fmt::format("run {} --out {} --quiet --duration 1e12", kShowcase, out),
                   "write less often (settings.output.every)");
  EXPECT_FALSE(fs::exists(out)) << "the first frame must be removed";
  expect_bad_input(fmt::format("run {} --out {} --quiet --duration 1e300", kShowcase, out), "more than any run can take");
  EXPECT_FALSE(fs::exists(out));
  // Without frames the probe rows alone are projected (they were still buffered, and counted 0).
  expect_bad_input(fmt::format("run {} --out {} --quiet --duration 1e12 --set settings.output.formats=[]", kShowcase, out),
                   "the run would write");
  // A file of an earlier run in the output directory is neither counted nor removed.
  fs::create_directories(out);
  std::ofstream(out + "/rigid_poses.csv") << "an earlier run's file\n";
  fs::last_write_time(out + "/rigid_poses.csv", fs::file_time_type::clock::now() - std::chrono::hours(1));
  std::ofstream(out + "/notes.txt") << "the user's file\n";
  expect_bad_input(fmt::format("run {} --out {} --quiet --duration 1e12 --set settings.output.formats=[]", kShowcase, out),
                   "the run would write");
  EXPECT_TRUE(fs::exists(out + "/rigid_poses.csv"));
  EXPECT_TRUE(fs::exists(out + "/notes.txt"));
  EXPECT_FALSE(fs::exists(out + "/probes.csv"));
}

TEST(CliBadInput, ResettingAWholeObjectWithSetIsRefused) {
  // --set settings={} used to reset every setting silently.
  expect_bad_input(fmt::format("check {} --set settings={{}}", kShowcase), "set its keys one at a time");
}

TEST(CliBadInput, OutputPlacesThatCannotHoldAnOutputDirectoryAreBadInput) {
  const std::string dir = test::temp_dir("outplace");
  std::ofstream(dir + "/file") << "x";
  expect_bad_input(fmt::format("run {} --duration 0.02 --out {}/file", kShowcase, dir), "is not a directory");
  expect_bad_input(fmt::format("run {} --duration 0.02 --out /proc/moreau-out", kShowcase), "cannot prepare the output");
  expect_bad_input(fmt::format("run {} --duration 0.02 --out /sys/moreau-out", kShowcase), "cannot prepare the output");
}

TEST(CliBadInput, ASceneNamedWithDotsWritesAVisibleCollection) {
  // "../../x" is made safe, and its .pvd must not become a hidden dotfile.
  const std::string dir = test::temp_dir("dots");
  std::ofstream(dir + "/dots.json") << R"({"name": "../../x", "settings": {"duration": 0.02},
    "objects": [{"name": "s", "kind": "rigid_body", "shape": {"type": "sphere", "radius": 0.1}, "position": [0, 1, 0]}]})";
  const test::CommandResult r = test::run_moreau(fmt::format("run {}/dots.json --out {}/out --quiet", dir, dir));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  int collections = 0;
  for (const auto& entry : fs::directory_iterator(dir + "/out"))
    if (entry.path().extension() == ".pvd") {
      ++collections;
      EXPECT_NE(entry.path().filename().string().front(), '.') << entry.path();
    }
  EXPECT_EQ(collections, 1);
}

TEST(CliNumericalFailure, ANonFiniteLoadNamesItselfAndTheTime) {
  // "1/(t-t)" gave 0 Newton iterations, a beam that never moved and exit 0; "0/0" an inverted
  // cell. Both are numerical failures naming the load's JSON path and t.
  for (const std::string load : {"1/(t-t)", "0/0"}) {
    const std::string scene = test::write_scene("nonfinite", fmt::format(R"({{"name": "beam",
      "settings": {{"solver": "fem", "integrator": "midpoint", "dt": 0.01, "duration": 0.05, "gravity": [0, 0, 0]}},
      "objects": [{{"name": "bar", "kind": "solid", "mesh": {{"type": "box", "min": [0, 0, 0], "max": [1, 0.1, 0.1], "cells": [4, 1, 1]}},
                  "material": {{"youngs_modulus": 1e6, "poisson_ratio": 0.3, "density": 1000}},
                  "dirichlet": [{{"where": {{"boundary": "left"}}, "value": [0, 0, 0]}}],
                  "loads": [{{"type": "traction", "where": {{"boundary": "right"}}, "value": [0, "{}", 0]}}]}}]}})",
                                                                         load));
    const std::string out = fs::path(scene).parent_path().string() + "/out";
    const test::CommandResult r = test::run_moreau(fmt::format("run {} --out {} --quiet", scene, out));
    EXPECT_EQ(r.exit_code, 3) << load << "\n" << r.output;
    EXPECT_NE(r.output.find("objects[0].loads[0].value[1]"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("at t = 0.005 s"), std::string::npos) << r.output;  // the midpoint rule loads at t + dt/2
    EXPECT_NE(r.output.find("step 1"), std::string::npos) << r.output;
    std::ifstream summary(out + "/run.json");
    ASSERT_TRUE(summary.good());
    EXPECT_EQ(nlohmann::json::parse(summary).at("status"), "failed");
  }
}

}  // namespace
}  // namespace moreau
