// The command line: exit codes and messages for every class of bad input; every example scene
// runs; results are bit-identical for 1 and 2 threads; cloth draped on a sphere stays outside it.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <nlohmann/json.hpp>

#include "test_helpers.hpp"

using namespace moreau;
namespace fs = std::filesystem;

namespace {

std::string write_scene(const std::string& tag, const std::string& text) {
  const std::string path = test::temp_dir(tag) + "/scene.json";
  std::ofstream(path) << text;
  return path;
}

const char* kValidCloth = R"({"name": "c", "settings": {"dt": 0.01, "substeps": 5, "duration": 0.05},
  "objects": [{"name": "cloth", "kind": "cloth", "mesh": {"type": "grid", "size": [1, 1], "resolution": [5, 5]},
               "material": {"area_density": 0.1}}]})";

// Expects exit code 2, a message containing every `needle`, and no output directory.
void expect_bad_input(const std::string& tag, const std::string& scene_text, const std::vector<std::string>& needles,
                      const std::string& extra_args = "") {
  const std::string scene = write_scene(tag, scene_text);
  const std::string out = fs::path(scene).parent_path() / "out";
  const auto r = test::run_moreau(fmt::format("run {} --out {} --quiet {}", scene, out, extra_args));
  EXPECT_EQ(r.exit_code, 2) << r.output;
  for (const auto& n : needles) EXPECT_NE(r.output.find(n), std::string::npos) << "missing '" << n << "' in: " << r.output;
  EXPECT_FALSE(fs::exists(out)) << "bad input must not leave output behind";
}

}  // namespace

TEST(CommandLine, MalformedJsonNamesLineAndColumn) {
  expect_bad_input("malformed", "{\n  \"name\": \"x\",\n  \"objects\": [,]\n}", {"scene.json:3:", "malformed JSON"});
}

TEST(CommandLine, UnknownKeyNamesItsJsonPath) {
  std::string text = kValidCloth;
  text.replace(text.find("\"area_density\""), 0, "\"aera\": 1, ");
  expect_bad_input("unknown", text, {"objects[0].material.aera", "unknown key", "area_density"});
}

TEST(CommandLine, WrongTypeAndOutOfRangeValues) {
  std::string text = kValidCloth;
  expect_bad_input("type", std::string(text).replace(text.find("0.01"), 4, "\"fast\""), {"settings.dt", "expected a number"});
  expect_bad_input("dt", std::string(text).replace(text.find("0.01"), 4, "-1"), {"settings.dt", "out of range"});
  expect_bad_input("density", std::string(text).replace(text.find("0.1}"), 3, "0"), {"area_density", "out of range"});
  expect_bad_input("poisson",
                   R"({"name": "s", "objects": [{"name": "b", "kind": "soft_body",
      "mesh": {"type": "box", "min": [0,0,0], "max": [1,1,1], "cells": [1,1,1]},
      "material": {"youngs_modulus": 1e5, "poisson_ratio": 0.5, "density": 1000}}]})",
                   {"poisson_ratio", "(-1, 0.5)"});
}

TEST(CommandLine, MissingMeshFileIsNamed) {
  expect_bad_input("mesh", R"({"name": "s", "objects": [{"name": "b", "kind": "soft_body",
      "mesh": {"type": "msh", "file": "no_such_mesh.msh"},
      "material": {"youngs_modulus": 1e5, "poisson_ratio": 0.3, "density": 1000}}]})",
                   {"no_such_mesh.msh", "cannot open"});
}

TEST(CommandLine, MixedInvertedTetrahedraAreRejectedAndAllInvertedAreRenumbered) {
  const std::string dir = test::temp_dir("inverted");
  // Two tetrahedra, one of them inverted (vertices 2 and 3 swapped).
  std::ofstream(dir + "/m.node") << "5 3 0 0\n0 0 0 0\n1 1 0 0\n2 0 1 0\n3 0 0 1\n4 1 1 1\n";
  std::ofstream(dir + "/m.ele") << "2 4 0\n0 0 1 2 3\n1 1 3 2 4\n";
  const std::string scene = dir + "/scene.json";
  std::ofstream(scene) << R"({"name": "s", "objects": [{"name": "b", "kind": "soft_body",
      "mesh": {"type": "tetgen", "file": "m"},
      "material": {"youngs_modulus": 1e5, "poisson_ratio": 0.3, "density": 1000}}]})";
  const auto r = test::run_moreau(fmt::format("check {}", scene));
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("inverted"), std::string::npos) << r.output;
  // Every tetrahedron inverted (a mirrored export) is one orientation convention: the reader swaps
  // two vertices of each, and the body falls exactly as the correctly numbered one does.
  std::ofstream(dir + "/good.ele") << "2 4 0\n0 0 1 2 3\n1 1 2 3 4\n";
  std::ofstream(dir + "/mirrored.ele") << "2 4 0\n0 0 1 3 2\n1 1 2 4 3\n";
  std::ofstream(dir + "/good.node") << "5 3 0 0\n0 0 0 0\n1 1 0 0\n2 0 1 0\n3 0 0 1\n4 1 1 1\n";
  std::ofstream(dir + "/mirrored.node") << "5 3 0 0\n0 0 0 0\n1 1 0 0\n2 0 1 0\n3 0 0 1\n4 1 1 1\n";
  std::vector<std::string> probes;
  for (const std::string base : {"good", "mirrored"}) {
    std::ofstream(dir + "/" + base + ".json") << fmt::format(R"({{"name": "{}", "settings": {{"dt": 0.01, "duration": 0.1}},
      "objects": [{{"name": "b", "kind": "soft_body", "mesh": {{"type": "tetgen", "file": "{}"}},
                   "material": {{"youngs_modulus": 1e5, "poisson_ratio": 0.3, "density": 1000}}}},
                  {{"name": "floor", "kind": "collider", "shape": {{"type": "plane", "point": [0, -0.05, 0]}}}}],
      "probes": [{{"name": "c", "type": "center_of_mass", "object": "b"}}]}})",
                                                              base, base);
    const auto run = test::run_moreau(fmt::format("run {}/{}.json --out {}/{}_out --quiet", dir, base, dir, base));
    ASSERT_EQ(run.exit_code, 0) << run.output;
    std::ifstream in(fmt::format("{}/{}_out/probes.csv", dir, base));
    probes.emplace_back(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  EXPECT_GT(probes[0].size(), 100u);
  EXPECT_EQ(probes[0], probes[1]);
}

TEST(CommandLine, BadSetOverrideAndUnknownSolver) {
  expect_bad_input("set", kValidCloth, {"settings.substeps", "out of range"}, "--set settings.substeps=0");
  std::string text = kValidCloth;
  expect_bad_input("solver", text.replace(text.find("\"dt\""), 0, "\"solver\": \"xpdb\", "),
                   {"settings.solver", "xpbd, nmd, xpbi"});
}

TEST(CommandLine, NmdSettingsNameTheirPathAndRange) {
  std::string text = kValidCloth;
  text.replace(text.find("\"dt\""), 0, "\"solver\": \"nmd\", ");
  expect_bad_input("nmd_omega", text, {"settings.nmd.over_relaxation", "out of range"},
                   "--set settings.nmd.over_relaxation=2");
  expect_bad_input("nmd_method", text, {"settings.nmd.method", "pgs, direct, hybrid"}, "--set settings.nmd.method='\"lcp\"'");
  expect_bad_input("nmd_key", text, {"settings.nmd", "iteration"}, "--set settings.nmd.iteration=3");
}

TEST(CommandLine, SuctionNamesWhatIsWrongAndXpbdRefusesIt) {
  const std::string cup = std::string(MOREAU_SOURCE_DIR) + "/scenes/meshes/suction_cup.obj";
  auto scene = [&](const std::string& solver, const std::string& mesh, const std::string& opening) {
    return fmt::format(R"({{"name": "s", "settings": {{"solver": "{}", "dt": 0.001}},
      "objects": [{{"name": "cup", "kind": "soft_body", "mesh": {},
                   "material": {{"youngs_modulus": 2e6, "poisson_ratio": 0.45, "density": 1100}},
                   "suction": {{"opening": {}}}}}]}})",
                       solver, mesh, opening);
  };
  const std::string obj = fmt::format(R"({{"type": "obj", "file": "{}", "quality": 2.5}})", cup);
  const std::string box = R"({"type": "box", "min": [0, 0, 0], "max": [0.1, 0.1, 0.1], "cells": [1, 1, 1]})";
  expect_bad_input("suction_xpbd", scene("xpbd", obj, "[0, -1, 0]"),
                   {"settings.solver", "does not simulate suction cups", "nmd"});
  expect_bad_input("suction_zero", scene("nmd", obj, "[0, 0, 0]"), {"objects[0].suction.opening", "nonzero"});
  // A box's faces looking down all lie in its bottom, the mouth: no cavity.
  expect_bad_input("suction_box", scene("nmd", box, "[0, -1, 0]"), {"objects[0].suction.opening", "no cavity"});
}

TEST(CommandLine, ExplosionExitsWithCodeThreeNamingStepTimeAndObject) {
  // Gravity of 1e4 m/s^2 on a 0.1 s step drives particles past settings.max_speed = 100 m/s in the first step.
  const std::string scene = write_scene("explode", R"({"name": "boom", "settings": {"dt": 0.1, "substeps": 1, "duration": 1, "max_speed": 100},
    "objects": [{"name": "sheet", "kind": "cloth", "velocity": [0, 0, 0],
      "mesh": {"type": "grid", "size": [1, 1], "resolution": [4, 4]},
      "material": {"area_density": 0.001, "stretch_compliance": 0}}]})");
  const std::string out = fs::path(scene).parent_path() / "out";
  const auto r = test::run_moreau(fmt::format("run {} --out {} --quiet --set settings.gravity=[0,-10000,0]", scene, out));
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_NE(r.output.find("step"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("'sheet'"), std::string::npos) << r.output;
}
TEST(CommandLine, FluidHeatAndGasInputErrorsNameTheirKey) {
  const std::string tank = R"({"name": "tank", "kind": "collider", "inside": true,
      "shape": {"type": "box", "center": [0, 0.5, 0], "half_extents": [0.5, 0.5, 0.5]}})";
  auto scene = [&](const std::string& thermal, const std::string& tank_keys = "", const std::string& solver = "xpbd") {
    return R"({"name": "f", "settings": {"dt": 0.005, "solver": ")" + solver + R"("}, "objects": [
      {"name": "tank", "kind": "collider", "inside": true)" + tank_keys + R"(,
       "shape": {"type": "box", "center": [0, 0.5, 0], "half_extents": [0.5, 0.5, 0.5]}},
      {"name": "w", "kind": "fluid", "particle_radius": 0.05, "block": {"min": [-0.5, 0, -0.5], "max": [0, 0.5, 0]})" +
           thermal + "}]}";
  };
  expect_bad_input("cold", scene(R"(, "thermal": {"temperature": -3})"), {"objects[1].thermal.temperature", "out of range"});
  expect_bad_input("thermal_key", scene(R"(, "thermal": {"melting": 300})"),
                   {"objects[1].thermal.melting", "unknown key", "melting_point"});
  expect_bad_input("latent_alone", scene(R"(, "thermal": {"latent_heat": 1e5})"),
                   {"objects[1].thermal.latent_heat", "melting_point"});
  expect_bad_input("melt_nmd", scene(R"(, "thermal": {"melting_point": 300})", "", "nmd"),
                   {"settings.solver", "melting", "'w'"});
  expect_bad_input("hot_wall_alone", scene("", R"(, "temperature": 400)"),
                   {"objects[0].temperature", "thermal"});
  expect_bad_input("hot_wall_unsampled", scene(R"(, "thermal": {})", R"(, "temperature": 400, "fluid_walls": false)"),
                   {"objects[0].temperature", "fluid_walls"});
  expect_bad_input("expansion_alone", scene(R"(, "thermal": {"expansion": 0.003})"),
                   {"objects[1].thermal.reference_temperature", "expansion", "density"});
  expect_bad_input("reference_alone", scene(R"(, "thermal": {"reference_temperature": 300})"),
                   {"objects[1].thermal.reference_temperature", "expansion"});
  expect_bad_input("expansion_huge", scene(R"(, "thermal": {"expansion": 2, "reference_temperature": 300})"),
                   {"objects[1].thermal.expansion", "out of range"});
  expect_bad_input("expansion_too_warm",
                   scene(R"(, "thermal": {"temperature": 500, "expansion": 0.004, "reference_temperature": 300})"),
                   {"objects[1].thermal.expansion", "0.8", "more than half"});
  expect_bad_input("gas_key", scene(R"(, "gas": {"breeze": [1, 0, 0]})"), {"objects[1].gas.breeze", "unknown key", "wind"});
  expect_bad_input("gas_drag", scene(R"(, "gas": {"drag": -1})"), {"objects[1].gas.drag", "out of range"});
  const std::string probe = R"(, "probes": [{"name": "t", "type": "temperature", "object": "w"}]})";
  std::string no_heat = scene("");
  no_heat.replace(no_heat.size() - 1, 1, probe);
  expect_bad_input("probe_no_heat", no_heat, {"probes[0].type", "thermal"});
}

TEST(CommandLine, FluidInputErrorsNameTheirKey) {
  const std::string tank = R"({"name": "tank", "kind": "collider", "inside": true,
      "shape": {"type": "box", "center": [0, 0.5, 0], "half_extents": [0.5, 0.5, 0.5]}})";
  auto scene = [&](const std::string& fluids) {
    return R"({"name": "f", "settings": {"dt": 0.005}, "objects": [)" + tank + ", " + fluids + "]}";
  };
  const std::string water = R"({"name": "w", "kind": "fluid", "particle_radius": 0.05,
      "block": {"min": [-0.5, 0, -0.5], "max": [0, 0.5, 0]}})";
  expect_bad_input("radii", scene(water + R"(, {"name": "oil", "kind": "fluid", "particle_radius": 0.04, "density": 800,
      "block": {"min": [0, 0, 0], "max": [0.5, 0.5, 0.5]}})"),
                   {"objects[2].particle_radius", "share one particle radius"});
  expect_bad_input("no_volume", scene(R"({"name": "w", "kind": "fluid", "particle_radius": 0.05})"),
                   {"objects[1].block", "exactly one of", "emitter"});
  expect_bad_input("no_blocks", scene(R"({"name": "w", "kind": "fluid", "particle_radius": 0.05, "blocks": [],
      "emitter": {"shape": "disc", "center": [0, 0.5, 0], "direction": [0, -1, 0], "radius": 0.1, "speed": 1}})"),
                   {"objects[1].blocks", "holds no block"});
  auto with_fluid_settings = [&](const std::string& fluid_settings, const std::string& objects) {
    return R"({"name": "f", "settings": {"dt": 0.005, "fluid": )" + fluid_settings + "}, \"objects\": [" + objects + "]}";
  };
  const std::string honey = R"({"name": "w", "kind": "fluid", "particle_radius": 0.05, "viscosity": 1e4,
      "block": {"min": [-0.5, 0, -0.5], "max": [0, 0.5, 0]}})";
  expect_bad_input("viscous", with_fluid_settings(R"({"viscosity_solver": "explicit"})", tank + ", " + honey),
                   {"objects[1].viscosity", "0.125 h^2 / nu", "implicit"});
  expect_bad_input("viscosity_solver", with_fluid_settings(R"({"viscosity_solver": "fast"})", tank + ", " + water),
                   {"settings.fluid.viscosity_solver", "explicit"});
  const std::string sticky_tank = R"({"name": "tank", "kind": "collider", "inside": true, "fluid_friction": 1,
      "shape": {"type": "box", "center": [0, 0.5, 0], "half_extents": [0.5, 0.5, 0.5]}})";
  expect_bad_input("friction_explicit", with_fluid_settings(R"({"viscosity_solver": "explicit"})", sticky_tank + ", " + water),
                   {"objects[0].fluid_friction", "implicit"});
  expect_bad_input("friction_range", with_fluid_settings("{}", R"({"name": "tank", "kind": "collider", "inside": true,
      "fluid_friction": 2, "shape": {"type": "box", "center": [0, 0.5, 0], "half_extents": [0.5, 0.5, 0.5]}}, )" + water),
                   {"objects[0].fluid_friction", "out of range"});
  const std::string paddle = R"({"name": "paddle", "kind": "rigid_body", "position": [0.2, 0.3, 0],
      "shape": {"type": "box", "half_extents": [0.01, 0.1, 0.1]}, )";
  expect_bad_input("body_friction_explicit",
                   with_fluid_settings(R"({"viscosity_solver": "explicit"})",
                                       tank + ", " + water + ", " + paddle + R"("fluid_friction": 1})"),
                   {"objects[2].fluid_friction", "implicit"});
  expect_bad_input("body_friction_range", with_fluid_settings("{}", tank + ", " + water + ", " + paddle + R"("fluid_friction": -1})"),
                   {"objects[2].fluid_friction", "out of range"});
  expect_bad_input("body_friction_uncoupled",
                   with_fluid_settings("{}", tank + ", " + water + ", " + paddle + R"("fluid_friction": 1, "fluid_coupling": false})"),
                   {"objects[2].fluid_friction", "fluid_coupling"});
  expect_bad_input("body_friction_inviscid",
                   with_fluid_settings("{}", tank + R"(, {"name": "w", "kind": "fluid", "particle_radius": 0.05, "viscosity": 0,
      "block": {"min": [-0.5, 0, -0.5], "max": [0, 0.5, 0]}}, )" + paddle + R"("fluid_friction": 1})"),
                   {"objects[2].fluid_friction", "viscosity"});
  expect_bad_input("body_friction_no_fluid", with_fluid_settings("{}", tank + ", " + paddle + R"("fluid_friction": 1})"),
                   {"objects[1].fluid_friction", "no particle fluid"});
  const std::string sheet = R"({"name": "sheet", "kind": "cloth", "material": {"area_density": 0.2},
      "mesh": {"type": "grid", "size": [0.2, 0.2], "resolution": [3, 3], "center": [0.2, 0.3, 0]}, )";
  expect_bad_input("cloth_friction_range", with_fluid_settings("{}", tank + ", " + honey + ", " + sheet + R"("fluid_friction": 1.5})"),
                   {"objects[2].fluid_friction", "out of range"});
  expect_bad_input("cloth_friction_uncoupled",
                   with_fluid_settings("{}", tank + ", " + honey + ", " + sheet + R"("fluid_friction": 1, "fluid_coupling": false})"),
                   {"objects[2].fluid_friction", "fluid_coupling"});
  expect_bad_input("soft_friction_explicit",
                   with_fluid_settings(R"({"viscosity_solver": "explicit"})", tank + ", " + water + R"(, {"name": "cube",
      "kind": "soft_body", "fluid_friction": 0.5, "mesh": {"type": "box", "min": [0.1, 0.1, -0.1], "max": [0.3, 0.3, 0.1], "cells": [1, 1, 1]},
      "material": {"youngs_modulus": 1e5, "poisson_ratio": 0.3, "density": 500}})"),
                   {"objects[2].fluid_friction", "implicit"});
  expect_bad_input("bulk_modulus", scene(R"({"name": "w", "kind": "fluid", "particle_radius": 0.05, "bulk_modulus": 0,
      "block": {"min": [-0.5, 0, -0.5], "max": [0, 0.5, 0]}})"),
                   {"objects[1].bulk_modulus", "out of range"});
  const std::string jet = R"({"name": "jet", "kind": "fluid", "particle_radius": 0.05, "emitter": )";
  expect_bad_input("emitter_both", scene(jet + R"({"shape": "disc", "center": [0, 0.5, 0], "direction": [0, -1, 0],
      "radius": 0.1, "speed": 1, "flow_rate": 0.01}})"),
                   {"objects[1].emitter.speed", "exactly one of \"speed\""});
  expect_bad_input("emitter_direction", scene(jet + R"({"shape": "rectangle", "center": [0, 0.5, 0], "direction": [0, 0, 0],
      "size": [0.2, 0.2], "speed": 1}})"),
                   {"objects[1].emitter.direction", "non-zero"});
  expect_bad_input("emitter_shape", scene(jet + R"({"shape": "star", "center": [0, 0.5, 0], "direction": [0, -1, 0]}})"),
                   {"objects[1].emitter.shape", "disc"});
  expect_bad_input("emitter_nozzle", scene(jet + R"({"shape": "disc", "center": [0, 0.5, 0], "direction": [0, -1, 0],
      "radius": 0.1, "speed": 1, "nozzle_length": -0.1}})"),
                   {"objects[1].emitter.nozzle_length", "out of range"});
  expect_bad_input("grain_nozzle", scene(R"({"name": "sand", "kind": "granular", "radius": 0.01, "emitter":
      {"shape": "disc", "center": [0, 0.5, 0], "direction": [0, -1, 0], "radius": 0.05, "speed": 1, "nozzle_length": 0.02}})"),
                   {"objects[1].emitter.nozzle_length", "a nozzle holds a stream of fluid or continuum"});
  // A second tank beside the first: the water in the first lies outside the second.
  expect_bad_input("two_tanks", scene(water + R"(, {"name": "second_tank", "kind": "collider", "inside": true,
      "shape": {"type": "box", "center": [2, 0.5, 0], "half_extents": [0.5, 0.5, 0.5]}})"),
                   {"objects[2].shape", "'w' starts outside this container", "inside every container"});
  expect_bad_input("jet_outside", scene(jet + R"({"shape": "disc", "center": [0, 1.5, 0], "direction": [0, -1, 0],
      "radius": 0.1, "speed": 1}})"),
                   {"objects[0].shape", "'jet' starts outside this container"});
  expect_bad_input("inside_plane", R"({"name": "f", "objects": [{"name": "p", "kind": "collider", "inside": true,
      "shape": {"type": "plane"}}]})",
                   {"objects[0].inside", "plane has no inside"});
  expect_bad_input("probe_kind", scene(water).replace(scene(water).size() - 1, 1,
                                                      R"(, "probes": [{"name": "h", "type": "fluid_height", "object": "tank", "at": [0, 0, 0]}]})"),
                   {"probes[0].object", "fluid object"});
}

TEST(CommandLine, RigidAndJointInputErrorsNameTheirKey) {
  auto scene = [](const std::string& body_extra, const std::string& joint) {
    return R"({"name": "r", "objects": [{"name": "a", "kind": "rigid_body", "shape": {"type": "box", "half_extents": [0.5, 0.5, 0.5]}, "position": [0, 0, 0])" +
           body_extra + R"(}], "joints": [)" + joint + "]}";
  };
  const std::string ok_joint = R"({"name": "j", "type": "spherical", "bodies": ["world", "a"], "anchor": [0, 1, 0]})";
  expect_bad_input("anchors_type", scene("", R"({"name": "j", "type": "distance", "bodies": ["world", "a"],
      "anchors": [[0, 2, 0], [0, "one", 0]]})"),
                   {"joints[0].anchors", "three numbers"});
  expect_bad_input("joint_body", scene("", R"({"name": "j", "type": "hinge", "bodies": ["world", "door"], "anchor": [0, 1, 0]})"),
                   {"joints[0].bodies", "'door'", "\"world\""});
  expect_bad_input("joint_self", scene("", R"({"name": "j", "type": "fixed", "bodies": ["a", "a"], "anchor": [0, 1, 0]})"),
                   {"joints[0].bodies", "itself"});
  expect_bad_input("joint_limits", scene("", R"({"name": "j", "type": "hinge", "bodies": ["world", "a"], "anchor": [0, 1, 0],
      "limits_deg": [30, -30]})"),
                   {"joints[0].limits_deg", "lower limit"});
  expect_bad_input("shape_type", R"({"name": "r", "objects": [{"name": "a", "kind": "rigid_body", "shape": {"type": "cone"}, "position": [0, 0, 0]}]})",
                   {"objects[0].shape.type", "sphere"});
  expect_bad_input("friction", scene(R"(, "friction": {"static": -0.5, "dynamic": 0.2})", ok_joint), {"objects[0].friction.static", "out of range"});
  expect_bad_input("friction", scene(R"(, "friction": -0.5)", ok_joint), {"objects[0].friction: -0.5 is out of range"});
  // extent, particle_count and escaped count particles: a rigid body has none to count.
  expect_bad_input("extent_of_body", R"({"name": "r", "objects": [{"name": "a", "kind": "rigid_body", "shape": {"type": "sphere", "radius": 0.1},
      "position": [0, 0, 0]}], "probes": [{"name": "low", "type": "extent", "object": "a", "axis": "y", "quantity": "min"}]})",
                   {"probes[0].object", "no particle (cloth, soft-body, granular, shape-matched or fluid) object named 'a'"});
}

TEST(CommandLine, FluidRunWritesParticlesAndWarnsAboutCfl) {
  // dt = 20 ms with 1 substep: water falling 0.4 m reaches ~2.8 m/s, CFL = 2.8 * 0.02 / 0.1 > 0.4.
  const std::string scene = write_scene("fluid_ok", R"({"name": "drop", "settings": {"dt": 0.02, "substeps": 1, "duration": 0.4},
    "objects": [{"name": "tank", "kind": "collider", "inside": true,
                 "shape": {"type": "box", "center": [0, 0.5, 0], "half_extents": [0.3, 0.5, 0.3]}},
                {"name": "water", "kind": "fluid", "particle_radius": 0.05,
                 "block": {"min": [-0.2, 0.4, -0.2], "max": [0.2, 0.8, 0.2]}}],
    "probes": [{"name": "n", "type": "particle_count", "object": "water"},
               {"name": "out", "type": "escaped", "object": "water", "box": {"min": [-0.3, 0, -0.3], "max": [0.3, 1, 0.3]}}]})");
  const std::string out = fs::path(scene).parent_path() / "out";
  const auto r = test::run_moreau(fmt::format("run {} --out {} --quiet", scene, out));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("CFL number"), std::string::npos) << r.output;
  EXPECT_TRUE(fs::exists(fs::path(out) / "frames/water_000000.vtp"));
  std::ifstream run(fs::path(out) / "run.json");
  const auto j = nlohmann::json::parse(run);
  EXPECT_EQ(j["counts"]["fluid_particles"], 64);
  EXPECT_GT(j["fluid"]["steps_over_cfl_limit"].get<int>(), 0);
  EXPECT_GT(j["fluid"]["max_cfl_number"].get<double>(), 0.4);
  std::ifstream csv(fs::path(out) / "probes.csv");
  std::string header, line, last;
  std::getline(csv, header);
  while (std::getline(csv, line)) last = line;
  EXPECT_EQ(header, "time,n,out");
  EXPECT_EQ(last.substr(last.find(',')), ",64,0");
}

TEST(CommandLine, ThermalFluidsWriteTemperaturesAndTheirProbes) {
  // A hot and a cold block of the same liquid, weightless, in an insulating tank: heat flows from
  // one to the other, and with one specific heat the mass-weighted mean temperature of both stays
  // at the mean of the start, 310 K. The frames carry the temperature and the liquid fraction.
  const std::string fluid = R"({{"name": "{}", "kind": "fluid", "particle_radius": 0.01,
      "block": {{"min": [{}, 0, 0], "max": [{}, 0.08, 0.08]}}, "thermal": {{"temperature": {}, "conductivity": 2000}}}})";
  const std::string scene = write_scene("thermal_ok", R"({"name": "heat", "settings": {"dt": 0.01, "substeps": 2, "duration": 1,
      "gravity": [0, 0, 0]}, "objects": [{"name": "tank", "kind": "collider", "inside": true,
      "shape": {"type": "box", "center": [0.08, 0.04, 0.04], "half_extents": [0.08, 0.04, 0.04]}}, )" +
      fmt::format(fmt::runtime(fluid), "cold", 0, 0.08, 300) + ", " + fmt::format(fmt::runtime(fluid), "hot", 0.08, 0.16, 320) + R"(],
    "probes": [{"name": "both", "type": "temperature", "object": "*"},
               {"name": "cold_max", "type": "temperature", "object": "cold", "quantity": "max"},
               {"name": "hot_min", "type": "temperature", "object": "hot", "quantity": "min"},
               {"name": "liquid", "type": "liquid_fraction", "object": "*"}]})");
  const std::string out = fs::path(scene).parent_path() / "out";
  const auto r = test::run_moreau(fmt::format("run {} --out {} --quiet", scene, out));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::ifstream frame(fs::path(out) / "frames/hot_000001.vtp");
  const std::string text((std::istreambuf_iterator<char>(frame)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("Name=\"temperature\""), std::string::npos);
  EXPECT_NE(text.find("Name=\"liquid_fraction\""), std::string::npos);
  std::ifstream csv(fs::path(out) / "probes.csv");
  std::string header, line, last;
  std::getline(csv, header);
  while (std::getline(csv, line)) last = line;
  EXPECT_EQ(header, "time,both,cold_max,hot_min,liquid");
  double time, both, cold_max, hot_min, liquid;
  ASSERT_EQ(std::sscanf(last.c_str(), "%lf,%lf,%lf,%lf,%lf", &time, &both, &cold_max, &hot_min, &liquid), 5) << last;
  EXPECT_NEAR(both, 310, 1e-9);
  EXPECT_GT(cold_max, 305);  // heat has crossed: the cold block's warmest particle has gained 5 K
  EXPECT_LT(hot_min, 315);
  EXPECT_EQ(liquid, 1);
}

TEST(CommandLine, AdhesionUnderXpbdIsAWarningNamingTheObjects) {
  // A cube glued under a ceiling: under xpbd its contacts cannot pull, so the run says so (and
  // the cube falls); under nmd it hangs and nothing is said.
  const std::string text = R"({"name": "glue", "settings": {"dt": 0.01, "duration": 0.1},
    "objects": [{"name": "ceiling", "kind": "collider", "shape": {"type": "box", "center": [0, 1.1, 0], "half_extents": [1, 0.1, 1]}},
                {"name": "cube", "kind": "rigid_body", "shape": {"type": "box", "half_extents": [0.1, 0.1, 0.1]},
                 "position": [0, 0.9, 0], "mass": 1, "adhesion": 30}]})";
  const std::string scene = write_scene("adhesion_xpbd", text);
  const std::string out = fs::path(scene).parent_path() / "out";
  const auto r = test::run_moreau(fmt::format("run {} --out {} --quiet", scene, out));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("warning: the \"adhesion\" of 'cube' acts only under \"solver\": \"nmd\""), std::string::npos)
      << r.output;
  const auto n = test::run_moreau(fmt::format("run {} --out {}_nmd --quiet --set 'settings.solver=\"nmd\"'", scene, out));
  ASSERT_EQ(n.exit_code, 0) << n.output;
  EXPECT_EQ(n.output.find("adhesion"), std::string::npos) << n.output;
}

TEST(CommandLine, ALightSheetGrippingAViscousFluidIsAWarning) {
  // A free sheet sliding along 10 Pa s liquid with fluid friction: at 0.83 ms substeps the liquid
  // it drags in one viscosity step weighs rho0 sqrt(nu h) = 2.9 kg/m^2 a side. A 0.3 kg/m^2 sheet
  // is warned about (it was flung to 2 m/s); a 3 kg/m^2 one, which slowed smoothly, is not.
  auto scene = [](double area_density) {
    return fmt::format(R"({{"name": "gap", "settings": {{"dt": 0.008333333333333333, "substeps": 10, "gravity": [0, 0, 0],
        "duration": 0.017}},
      "objects": [
        {{"name": "box", "kind": "collider", "inside": true, "friction": 0,
          "shape": {{"type": "box", "center": [0.02, 0.3, 0.012], "half_extents": [0.03, 0.4, 0.012]}}}},
        {{"name": "sheet", "kind": "cloth", "fluid_friction": 1, "velocity": [0, 0.1, 0], "friction": 0, "collider_gap": 0,
          "mesh": {{"type": "grid", "size": [0.3, 0.022], "resolution": [31, 4], "center": [0.042, 0.4, 0.012],
                   "rotation_deg": [0, 0, 90]}},
          "material": {{"area_density": {}, "stretch_compliance": 0}}}},
        {{"name": "liquid", "kind": "fluid", "particle_radius": 0.002, "viscosity": 10, "xsph": 0,
          "block": {{"min": [0, 0.3, 0], "max": [0.04, 0.5, 0.024]}}}}]}})",
                       area_density);
  };
  const std::string light = write_scene("light_sheet", scene(0.3));
  const auto r = test::run_moreau(fmt::format("run {} --out {} --quiet", light, (fs::path(light).parent_path() / "out").string()));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("warning: 'sheet' grips the particle fluid (\"fluid_friction\") but its surface weighs 0.3 "
                          "kg/m^2, less than the 2.89 kg/m^2"),
            std::string::npos)
      << r.output;
  const std::string heavy = write_scene("heavy_sheet", scene(3.0));
  const auto n = test::run_moreau(fmt::format("run {} --out {} --quiet", heavy, (fs::path(heavy).parent_path() / "out").string()));
  ASSERT_EQ(n.exit_code, 0) << n.output;
  EXPECT_EQ(n.output.find("grips the particle fluid"), std::string::npos) << n.output;
}

TEST(CommandLine, VersionHelpAndOutputDirectory) {
  EXPECT_EQ(test::run_moreau("--version").exit_code, 0);
  EXPECT_EQ(test::run_moreau("--help").exit_code, 0);
  const std::string scene = write_scene("ok", kValidCloth);
  const std::string out = fs::path(scene).parent_path() / "out";
  const auto r = test::run_moreau(fmt::format("run {} --out {} --quiet", scene, out));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const char* f : {"run.json", "probes.csv", "c.pvd", "frames/cloth_000000.vtu", "frames/cloth_000005.vtu"})
    EXPECT_TRUE(fs::exists(fs::path(out) / f)) << f;
  std::ifstream run(fs::path(out) / "run.json");
  const auto j = nlohmann::json::parse(run);
  EXPECT_EQ(j["steps"], 5);
  EXPECT_TRUE(j.contains("wall_time_s"));
  EXPECT_TRUE(j["stage_time_s"].contains("distance"));
}

TEST(Scenes, EveryExampleSceneRunsBriefly) {
  for (const auto& entry : fs::directory_iterator(fs::path(MOREAU_SOURCE_DIR) / "scenes")) {
    if (entry.path().extension() != ".json") continue;
    // A steady scene solves completely whatever --duration says; this one takes 20 s and is run
    // on a coarser mesh by FlowScenes.Cavity3DSceneWithGmresMatchesUmfpackAndIsMirrorSymmetric.
    if (entry.path().filename() == "cavity3d_re400.json") continue;
    // The immersed scenes (the two-leaflet channel, the flag, the bodies falling in a fluid) take
    // a second or more per step: a step or a few. The largest particle scenes (tens of thousands
    // of grains or continuum particles, several seconds per 0.1 s) run 0.02 s.
    static const std::map<std::string, const char*> kShortRuns = {
        {"two_leaflet_valve.json", "0.003"}, {"sedimenting_disc.json", "0.006"}, {"fluttering_plate.json", "0.004"},
        {"turek_hron_fsi2.json", "0.015"},   {"wheel_on_sand.json", "0.02"},     {"snowball_wall.json", "0.02"},
        {"sand_column_xpbi.json", "0.02"},   {"sand_castle_wave.json", "0.02"},  {"suction_cup.json", "0.02"},
        {"putty_balls.json", "0.02"}};
    const std::string file = entry.path().filename().string();
    const auto short_run = kShortRuns.find(file);
    const char* duration = short_run == kShortRuns.end() ? "0.1" : short_run->second;
    const std::string out = test::temp_dir("smoke") + "/out";
    const auto r = test::run_moreau(fmt::format("run {} --out {} --quiet --duration {}", entry.path().string(), out, duration));
    EXPECT_EQ(r.exit_code, 0) << entry.path() << ": " << r.output;
  }
}

TEST(Determinism, ShowcaseIsBitIdenticalForOneAndTwoThreads) {
  const std::string scene = fs::path(MOREAU_SOURCE_DIR) / "scenes" / "showcase.json";
  Scene one = load_scene(scene, {"settings.threads=1"});
  Scene two = load_scene(scene, {"settings.threads=2"});
  test::run_steps(one, 60);
  test::run_steps(two, 60);
  ASSERT_EQ(one.state.position.size(), two.state.position.size());
  for (size_t p = 0; p < one.state.position.size(); ++p) {
    ASSERT_EQ(one.state.position[p], two.state.position[p]) << "particle " << p;
    ASSERT_EQ(one.state.velocity[p], two.state.velocity[p]) << "particle " << p;
  }
}

TEST(ClothValidation, ClothDrapedOverSphereEndsWithNoVertexInside) {
  Scene s = test::scene_from_json(R"({"name": "drape", "settings": {"dt": 0.01, "substeps": 20},
    "objects": [
      {"name": "ball", "kind": "collider", "shape": {"type": "sphere", "center": [0, 0.5, 0], "radius": 0.3}, "friction": 0.3},
      {"name": "floor", "kind": "collider", "shape": {"type": "plane"}},
      {"name": "cloth", "kind": "cloth", "mesh": {"type": "grid", "size": [1.2, 1.2], "resolution": [30, 30], "center": [0, 1, 0]},
       "material": {"area_density": 0.2, "bending_stiffness": 1e-5}}]})");
  test::run_steps(s, 150);
  const Index cloth = s.model.find_object("cloth");
  Real min_distance = 1e9;
  for (Index p = s.model.objects[cloth].particle_begin; p < s.model.objects[cloth].particle_end; ++p)
    min_distance = std::min(min_distance, (s.state.position[p] - Vec3(0, 0.5, 0)).norm() - 0.3);
  // Every vertex keeps at least its collider gap (the collision radius, half an edge, ~2 cm)
  // from the sphere, up to round-off of the final projection.
  EXPECT_GE(min_distance, s.model.particle_collider_gap[s.model.objects[cloth].particle_begin] - 1e-9);
  // And the cloth really draped: its centre rests on the top of the sphere.
  EXPECT_LT(s.state.position[s.model.objects[cloth].particle_begin + 15 * 30 + 15].y(), 0.85);
}

namespace moreau {
namespace {

TEST(CommandLine, ClothMassIsAnAreaDensityOrAVertexMassNotBoth) {
  std::string both = kValidCloth;
  both.replace(both.find("\"area_density\": 0.1"), 19, "\"area_density\": 0.1, \"vertex_mass\": 1");
  expect_bad_input("cloth-both-masses", both, {"objects[0].material.area_density", "vertex_mass"});
  std::string neither = kValidCloth;
  neither.replace(neither.find("\"area_density\": 0.1"), 19, "\"damping\": 0.0");
  expect_bad_input("cloth-no-mass", neither, {"objects[0].material.area_density", "vertex_mass"});
  // Given per vertex, every particle has that mass, the pinned ones included (their inverse mass is 0).
  std::string per_vertex = kValidCloth;
  per_vertex.replace(per_vertex.find("\"area_density\": 0.1"), 19, "\"vertex_mass\": 0.7");
  const Scene s = test::scene_from_json(per_vertex);
  ASSERT_EQ(s.model.particle_count(), 25);
  for (Index p = 0; p < s.model.particle_count(); ++p) EXPECT_EQ(s.model.particle_mass[p], 0.7);
}

}  // namespace
}  // namespace moreau
