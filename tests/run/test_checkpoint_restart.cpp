// Checkpoints restart bit for bit: a run of 2T and a run of T that writes a checkpoint, restored
// into a fresh World and run for T more, end in the same state — compared as the bytes of a
// checkpoint of each, which hold every field of the state (contacts, warm starts, neighbour
// lists, the flow's history and lagged preconditioner) — and the continued output directory
// holds the same probes.csv and frames as the uninterrupted run's. Every engine and solver:
// XPBD with every material, rigid bodies, a fluid, a freezing fluid, smoke in open air (its
// concentration), nmd with suction cups (warm starts), xpbi sand
// under a rigid wheel, FEM solids with rigid bodies and joints, and a transient flow with the
// direct and the GMRES solver.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "checkpoint_restart_check.hpp"
#include "moreau/moreau.hpp"
#include "scene_test_helpers.hpp"

namespace moreau::test {
namespace {

namespace fs = std::filesystem;

// Cloth, a soft body, a fluid, a rigid body, a rod, grains and a shape-matched body in one tank,
// low enough that they touch the floor and each other within a few steps.
constexpr const char* kEveryMaterial = R"({"name": "every_material",
  "settings": {"dt": 0.004, "substeps": 4, "iterations": 2, "duration": 1.0},
  "objects": [
    {"name": "tank", "kind": "collider", "inside": true,
     "shape": {"type": "box", "center": [0, 0.4, 0], "half_extents": [0.5, 0.4, 0.2]}},
    {"name": "water", "kind": "fluid", "particle_radius": 0.02, "density": 1000,
     "block": {"min": [-0.5, 0, -0.2], "max": [-0.3, 0.2, 0.2]}},
    {"name": "block", "kind": "soft_body",
     "mesh": {"type": "box", "min": [-0.25, 0.0, -0.05], "max": [-0.15, 0.08, 0.05], "cells": [3, 2, 3]},
     "material": {"model": "neo_hookean", "youngs_modulus": 1e5, "poisson_ratio": 0.35, "density": 800}},
    {"name": "sheet", "kind": "cloth",
     "mesh": {"type": "grid", "size": [0.2, 0.2], "resolution": [8, 8], "center": [-0.2, 0.12, 0]},
     "material": {"area_density": 0.5, "stretch_compliance": 1e-7, "bending_stiffness": 1e-4}},
    {"name": "crate", "kind": "rigid_body", "shape": {"type": "box", "half_extents": [0.04, 0.04, 0.04]},
     "position": [0.0, 0.05, 0.0], "friction": 0.5},
    {"name": "rope", "kind": "rod", "points": [[0.05, 0.15, 0], [0.1, 0.15, 0], [0.15, 0.15, 0]], "radius": 0.005,
     "youngs_modulus": 2e7, "poisson_ratio": 0.3, "density": 1150, "friction": 0.5},
    {"name": "sand", "kind": "granular", "blocks": [{"min": [0.2, 0.0, -0.04], "max": [0.28, 0.08, 0.04]}],
     "radius": 0.01, "density": 2600, "friction": 0.5},
    {"name": "cube", "kind": "shape_matched", "blocks": [{"min": [0.35, 0.0, -0.04], "max": [0.43, 0.08, 0.04]}],
     "radius": 0.01, "density": 600, "friction": 0.6}
  ],
  "probes": [{"name": "crate", "type": "center_of_mass", "object": "crate"},
             {"name": "water_front", "type": "extent", "object": "water", "axis": "x", "quantity": "max"}]})";

using Case = RestartCase;

class CheckpointRestart : public ::testing::TestWithParam<Case> {};

TEST_P(CheckpointRestart, RunOfTwoTEqualsRunOfTThenRestartForT) { expect_seamless_restart(GetParam()); }

INSTANTIATE_TEST_SUITE_P(
    Engines, CheckpointRestart,
    ::testing::Values(Case{"XpbdEveryMaterial", kEveryMaterial, {}, 15},
                      Case{"RigidStack", "stack_knockdown.json", {}, 30},
                      Case{"Fluid", "dam_break.json", {"objects.water.particle_radius=0.02"}, 20},
                      Case{"FreezingFluid", "lava_flow.json", {}, 20},
                      Case{"SmokeInOpenAir", "smoke_plume.json", {}, 40},
                      Case{"NmdSuction", "suction_lift.json", {}, 20},
                      Case{"NmdEveryMaterial", kEveryMaterial, {"settings.solver=\"nmd\""}, 10},
                      Case{"XpbiWheelOnSand", "wheel_on_sand.json", {"objects.sand.spacing=0.01"}, 8},
                      Case{"FemSolidsBodiesJoints", "fem_hinged_beam.json", {}, 6},
                      Case{"TransientFlowDirect", kTransientCavity, {}, 3},
                      Case{"ImmersedSolids", "two_leaflet_valve.json",
                           {"objects.blood.mesh.cells=[64,16]", "objects.top_leaflet.mesh.cells=[2,10]",
                            "objects.bottom_leaflet.mesh.cells=[2,10]", "settings.output.every=2"},
                           6},
                      Case{"ImmersedRigidBody", "sedimenting_disc.json",
                           {"objects.water.mesh.cells=[16,48]", "settings.output.every=2"}, 6},
                      Case{"TransientFlowGmres", kTransientCavity, {"settings.linear_solver={\"type\": \"gmres\"}"}, 3}),
    [](const auto& info) { return std::string(info.param.name); });

// A checkpoint restores only into the scene that wrote it; anything else is refused with the
// file named, and the state is left as it was.
TEST(Checkpoint, RefusesAnotherSceneAndDamagedFiles) {
  const std::string dir = temp_dir("restart-refusals");
  World cloth = World::load(scene_path("tablecloth.json"));
  for (int s = 0; s < 3; ++s) cloth.step();
  cloth.save_checkpoint(dir + "/cloth.bin");

  World other = World::load(scene_path("stack_knockdown.json"));
  try {
    other.restore(dir + "/cloth.bin");
    ADD_FAILURE() << "a checkpoint of another scene was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("written for scene 'tablecloth'"), std::string::npos) << e.what();
  }
  EXPECT_EQ(other.time(), 0.0);

  // The same scene with other physics (a --set that changes the model) is another scene.
  World heavier = World::load(scene_path("tablecloth.json"), {"settings.gravity=[0,-20,0]"});
  EXPECT_THROW(heavier.restore(dir + "/cloth.bin"), InputError);
  // ... but another duration, output cadence or thread count is the same scene.
  World longer = World::load(scene_path("tablecloth.json"), {"settings.duration=9", "settings.output.every=3"});
  longer.restore(dir + "/cloth.bin");
  EXPECT_EQ(longer.time(), cloth.time());

  const std::string bytes = file_bytes(dir + "/cloth.bin");
  std::ofstream(dir + "/truncated.bin", std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  std::string flipped = bytes;
  flipped[flipped.size() / 2] ^= 0x40;
  std::ofstream(dir + "/flipped.bin", std::ios::binary) << flipped;
  std::ofstream(dir + "/garbage.bin") << "{\"not\": \"a checkpoint\"}";
  const std::pair<const char*, const char*> damaged[] = {
      {"truncated.bin", "truncated"}, {"flipped.bin", "damaged"}, {"garbage.bin", "not a moreau checkpoint"},
      {"missing.bin", "cannot open"}};
  World fresh = World::load(scene_path("tablecloth.json"));
  for (const auto& [file, expected] : damaged) {
    try {
      fresh.restore(dir + "/" + file);
      ADD_FAILURE() << file << " was accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(file), std::string::npos) << e.what();
    }
  }
  EXPECT_EQ(fresh.time(), 0.0);
}

}  // namespace
}  // namespace moreau::test
