// "solver": "fem" scenes through the command line: a static tension test against the exact
// homogeneous solution, a dynamic run's energy after a load pulse, output files, and bad input.
#include <gtest/gtest.h>

#include <iterator>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>

#include "moreau/materials/hyperelastic.hpp"
#include "fem_test_helpers.hpp"
#include "scene_test_helpers.hpp"

namespace moreau {
namespace {

namespace fs = std::filesystem;

using test::read_probes;
using test::run_scene;
using test::write_scene;

TEST(FemScenes, StaticUniaxialTensionMatchesTheHomogeneousSolution) {
  // A 1 x 0.2 x 0.2 m Neo-Hookean block on rollers (u_x = 0 on the left, u_y = 0 on the bottom,
  // u_z = 0 at the back; the other components free) pulled by a reference traction P on its right
  // face, ramped over 4 load steps (value "P*t", t = 0.25 ... 1). The exact solution is homogeneous,
  // F = diag(l1, l2, l2) with P_11 = l1 S_11 = P and S_22 = 0,
  //   S = mu (I - C^-1) + lambda ln J C^-1,  J = l1 l2^2,
  // which every mesh reproduces (patch test): the right face moves by (l1 - 1) L to Newton's
  // tolerance. Here P = 0.3 E gives a 25 % stretch.
  const Real E = 1e6, nu = 0.3, P = 3e5;
  const std::string scene = write_scene("fem_tension", fmt::format(R"({{"name": "tension",
    "settings": {{"solver": "fem", "integrator": "static", "dt": 0.25, "duration": 1, "gravity": [0, 0, 0],
                 "newton": {{"tolerance": 1e-12}}}},
    "objects": [{{"name": "bar", "kind": "solid", "mesh": {{"type": "box", "min": [0, 0, 0], "max": [1, 0.2, 0.2], "cells": [5, 2, 2]}},
                "material": {{"youngs_modulus": {}, "poisson_ratio": {}, "density": 1000}},
                "loads": [{{"type": "traction", "where": {{"boundary": "right"}}, "value": ["{}*t", 0, 0]}}],
                "dirichlet": [{{"where": {{"boundary": "left"}}, "value": [0, null, null]}},
                              {{"where": {{"boundary": "bottom"}}, "value": [null, 0, null]}},
                              {{"where": {{"boundary": "back"}}, "value": [null, null, 0]}}]}}],
    "probes": [{{"name": "end", "type": "point", "object": "bar", "nearest": [1, 0.2, 0.2]}},
               {{"name": "newton", "type": "newton_iterations"}}]}})",
                                                                   E, nu, P));
  const std::string out = fs::path(scene).parent_path() / "out";
  const auto rows = run_scene(scene, out);
  // The exact stretches by Newton on (P_11 - P, S_22).
  const LameParameters lame = lame_from_youngs(E, nu);
  auto residual = [&](Real l1, Real l2) {
    const Real lnJ = std::log(l1 * l2 * l2);
    const Real S11 = lame.mu * (1 - 1 / (l1 * l1)) + lame.lambda * lnJ / (l1 * l1);
    const Real S22 = lame.mu * (1 - 1 / (l2 * l2)) + lame.lambda * lnJ / (l2 * l2);
    return Vec2(l1 * S11 - P, S22);
  };
  const Vec2 l = test::solve_two(residual, Vec2(1.2, 0.95));
  ASSERT_LT(residual(l.x(), l.y()).norm(), 1e-6);
  ASSERT_EQ(rows.size(), 5u);  // t = 0 and four load steps
  EXPECT_NEAR(rows.back()[1], l.x() - 1, 1e-9);
  EXPECT_NEAR(rows.back()[2], 0.2 * (l.y() - 1), 1e-9);
  EXPECT_NEAR(rows.back()[3], 0.2 * (l.y() - 1), 1e-9);
  EXPECT_GT(l.x(), 1.2);
  EXPECT_TRUE(fs::exists(out + "/tension.pvd"));
  EXPECT_TRUE(fs::exists(out + "/frames/bar_000004.vtu"));
  std::ifstream frame(out + "/frames/bar_000004.vtu");
  const std::string xml((std::istreambuf_iterator<char>(frame)), std::istreambuf_iterator<char>());
  EXPECT_NE(xml.find("Name=\"cauchy_stress\" NumberOfComponents=\"6\""), std::string::npos);
  EXPECT_NE(xml.find("Name=\"von_mises\""), std::string::npos);
}

TEST(FemScenes, GmshMeshWithPhysicalGroupsSolvesPlaneStrainTension) {
  // A 2 x 1 m plate of two quads written as a Gmsh MSH 4.1 file with physical curves "left" and
  // "right": rollers on "left" (u_x = 0) and at the origin (u_y = 0), a reference traction
  // P = 0.2 E on "right". Plane strain: the exact solution is homogeneous, F = diag(l1, l2, 1)
  // with P_11 = l1 S_11 = P and S_22 = 0; the corner (2, 1) moves by (2 (l1 - 1), l2 - 1) to
  // Newton's tolerance.
  const std::string dir = test::temp_dir("fem_msh");
  std::ofstream(dir + "/plate.msh") << R"($MeshFormat
4.1 0 8
$EndMeshFormat
$PhysicalNames
3
1 1 "left"
1 2 "right"
2 3 "plate"
$EndPhysicalNames
$Entities
0 2 1 0
1 0 0 0 0 1 0 1 1 0
2 2 0 0 2 1 0 1 2 0
1 0 0 0 2 1 0 1 3 0
$EndEntities
$Nodes
1 6 1 6
2 1 0 6
1
2
3
4
5
6
0 0 0
1 0 0
2 0 0
0 1 0
1 1 0
2 1 0
$EndNodes
$Elements
3 4 1 4
1 1 1 1
1 1 4
1 2 1 1
2 3 6
2 1 3 2
3 1 2 5 4
4 2 3 6 5
$EndElements
)";
  const Real E = 1e6, nu = 0.3, P = 2e5;
  const std::string scene = dir + "/scene.json";
  std::ofstream(scene) << fmt::format(R"({{"name": "plate",
    "settings": {{"solver": "fem", "integrator": "static", "dt": 0.5, "duration": 1, "gravity": [0, 0, 0],
                 "newton": {{"tolerance": 1e-12}}, "output": {{"formats": []}}}},
    "objects": [{{"name": "plate", "kind": "solid", "mesh": {{"type": "msh", "file": "plate.msh"}},
                "material": {{"youngs_modulus": {}, "poisson_ratio": {}, "density": 1000}},
                "loads": [{{"type": "traction", "where": {{"boundary": "right"}}, "value": ["{}*t", 0]}}],
                "dirichlet": [{{"where": {{"boundary": "left"}}, "value": [0, null]}},
                              {{"where": {{"box": {{"min": [-0.1, -0.1], "max": [0.1, 0.1]}}}}, "value": [null, 0]}}]}}],
    "probes": [{{"name": "corner", "type": "point", "object": "plate", "nearest": [2, 1]}}]}})",
                                      E, nu, P);
  const auto rows = run_scene(scene, dir + "/out");
  const LameParameters lame = lame_from_youngs(E, nu);
  auto residual = [&](Real l1, Real l2) {
    const Real lnJ = std::log(l1 * l2);
    return Vec2(l1 * (lame.mu * (1 - 1 / (l1 * l1)) + lame.lambda * lnJ / (l1 * l1)) - P,
                lame.mu * (1 - 1 / (l2 * l2)) + lame.lambda * lnJ / (l2 * l2));
  };
  const Vec2 l = test::solve_two(residual, Vec2(1.2, 0.95));
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_NEAR(rows.back()[1], 2 * (l.x() - 1), 1e-9);
  EXPECT_NEAR(rows.back()[2], l.y() - 1, 1e-9);
  // Every cell numbered clockwise (all Jacobians negative, as some exporters write a mirrored
  // part): the reader reverses each cell's numbering, and the solution is the same (the same
  // equations summed in another order, solved to Newton's 1e-12: equal to round-off, 1e-12 m).
  std::string reversed_text;
  {
    std::ifstream in(dir + "/plate.msh");
    reversed_text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  reversed_text.replace(reversed_text.find("3 1 2 5 4"), 9, "3 4 5 2 1");
  reversed_text.replace(reversed_text.find("4 2 3 6 5"), 9, "4 5 6 3 2");
  std::ofstream(dir + "/reversed.msh") << reversed_text;
  std::string reversed_scene_text;
  {
    std::ifstream in(scene);
    reversed_scene_text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  reversed_scene_text.replace(reversed_scene_text.find("plate.msh"), 9, "reversed.msh");
  std::ofstream(dir + "/reversed.json") << reversed_scene_text;
  const auto reversed_rows = run_scene(dir + "/reversed.json", dir + "/reversed_out");
  ASSERT_EQ(reversed_rows.size(), 3u);
  EXPECT_NEAR(reversed_rows.back()[1], rows.back()[1], 1e-12);
  EXPECT_NEAR(reversed_rows.back()[2], rows.back()[2], 1e-12);
  // A boundary the file does not name is reported with the names it does.
  std::ofstream(dir + "/bad.json") << R"({"name": "bad", "settings": {"solver": "fem"},
    "objects": [{"name": "p", "kind": "solid", "mesh": {"type": "msh", "file": "plate.msh"}, "material": {"youngs_modulus": 1e6, "poisson_ratio": 0.3, "density": 1},
                "dirichlet": [{"where": {"boundary": "top"}, "value": [0, 0]}]}]})";
  const auto bad = test::run_moreau(fmt::format("run {} --out {} --quiet", dir + "/bad.json", dir + "/bad_out"));
  EXPECT_EQ(bad.exit_code, 2) << bad.output;
  EXPECT_NE(bad.output.find("allowed: left, right"), std::string::npos) << bad.output;
}

TEST(FemScenes, DynamicRunKeepsEnergyAfterAPulse) {
  // A clamped hex8 beam pushed at its tip for 0.5 s (value "1*(t<0.5)" per node), then free:
  // with the energy-momentum scheme the total energy after the pulse stays constant to 1e-9
  // relative (Newton tolerance 1e-10) over 75 steps of 0.02 s.
  const std::string scene = write_scene("fem_beam", R"J({"name": "beam",
    "settings": {"solver": "fem", "dt": 0.02, "duration": 2, "integrator": "energy_momentum", "gravity": [0, 0, 0]},
    "objects": [{"name": "beam", "kind": "solid", "mesh": {"type": "box", "min": [0, 0, 0], "max": [1, 0.1, 0.1], "cells": [20, 2, 2]},
                "material": {"model": "neo_hookean", "youngs_modulus": 1e7, "poisson_ratio": 0.3, "density": 1000},
                "loads": [{"type": "nodal_force", "where": {"box": {"min": [0.9, -1, -1], "max": [2, 2, 2]}},
                           "value": ["0", "1*(t<0.5)", "0"]}],
                "dirichlet": [{"where": {"boundary": "left"}, "value": ["0", "0", "0"]}]}],
    "probes": [{"name": "E", "type": "energy", "quantity": "total"}, {"name": "tip", "type": "point", "object": "beam",
                "nearest": [1, 0.05, 0.05], "quantity": "velocity"}]})J");
  const std::string out = fs::path(scene).parent_path() / "out";
  const auto rows = run_scene(scene, out);
  ASSERT_EQ(rows.size(), 101u);
  Real reference = 0, drift = 0, speed = 0;
  for (const auto& row : rows) {
    if (row[0] < 0.5 + 1e-9) continue;
    if (reference == 0) reference = row[1];
    drift = std::max(drift, std::abs(row[1] - reference));
    speed = std::max(speed, std::abs(row[3]));
  }
  EXPECT_GT(reference, 0.1);  // the pulse did work
  EXPECT_GT(speed, 0.01);     // and the beam vibrates
  EXPECT_LT(drift, 1e-9 * reference);
}

TEST(FemScenes, ProbesSpeakTheConstraintEnginesVocabulary) {
  // A 1 x 0.5 x 0.2 m box body thrown at v = (1, 2, 0) m/s spinning at 3 rad/s about z (a
  // principal axis) without gravity, and a free solid beside it, for 10 steps of 0.01 s:
  //   center_of_mass = x0 + v t    the midpoint rule moves a free centre exactly: 1e-12 m
  //   velocity = v                 1e-12 m/s
  //   angular_velocity = (0, 0, 3) steady rotation about a principal axis; the scheme keeps it to
  //                                its Newton tolerance (1e-12 relative here): 1e-9 rad/s
  //   frame "body": along d1, the axis of the smallest Euler-tensor value, which is z
  //   a point probe by "vertex" reads the node a "nearest" probe finds at that node's position.
  const std::string scene = write_scene("fem_probe_vocabulary", R"J({"name": "probes",
    "settings": {"solver": "fem", "dt": 0.01, "duration": 0.1, "integrator": "energy_momentum", "gravity": [0, 0, 0],
                 "newton": {"tolerance": 1e-12}},
    "objects": [{"name": "box", "kind": "rigid_body", "mesh": {"type": "box", "min": [-0.5, -0.25, -0.1], "max": [0.5, 0.25, 0.1],
                 "cells": [4, 2, 1]}, "density": 1000, "velocity": [1, 2, 0], "angular_velocity": [0, 0, 3]},
                {"name": "cube", "kind": "solid", "mesh": {"type": "box", "min": [2, 0, 0], "max": [2.2, 0.2, 0.2], "cells": [1, 1, 1]},
                 "material": {"youngs_modulus": 1e5, "poisson_ratio": 0.3, "density": 1000}}],
    "probes": [{"name": "c", "type": "center_of_mass", "object": "box"},
               {"name": "v", "type": "velocity", "object": "box"},
               {"name": "w", "type": "angular_velocity", "object": "box"},
               {"name": "wb", "type": "angular_velocity", "object": "box", "frame": "body"},
               {"name": "by_index", "type": "point", "object": "cube", "vertex": 0, "quantity": "position"},
               {"name": "by_place", "type": "point", "object": "cube", "nearest": [2, 0, 0], "quantity": "position"},
               {"name": "E", "type": "energy", "object": "*"}]})J");
  const std::string out = fs::path(scene).parent_path() / "out";
  const auto rows = run_scene(scene, out);
  ASSERT_EQ(rows.size(), 11u);
  for (const auto& r : rows) {
    const Real t = r[0];
    EXPECT_NEAR(r[1], 1 * t, 1e-12);
    EXPECT_NEAR(r[2], 2 * t, 1e-12);
    EXPECT_NEAR(r[3], 0, 1e-12);
    EXPECT_NEAR(r[4], 1, 1e-12);
    EXPECT_NEAR(r[5], 2, 1e-12);
    EXPECT_NEAR(r[7], 0, 1e-9);
    EXPECT_NEAR(r[8], 0, 1e-9);
    EXPECT_NEAR(r[9], 3, 1e-9);
    EXPECT_NEAR(std::abs(r[10]), 3, 1e-9);
    EXPECT_NEAR(r[11], 0, 1e-9);
    EXPECT_NEAR(r[12], 0, 1e-9);
    for (int k = 0; k < 3; ++k) EXPECT_EQ(r[13 + k], r[16 + k]) << "t = " << t;
  }
  EXPECT_NEAR(rows.front()[13], 2, 1e-15);
}

TEST(FemScenes, StrongPulseAsksForASmallerStepAndRunsWithIt) {
  // A free plane-strain bar (1 x 0.1 m, 40 x 4 cells, 100 kg/m^3: 10 kg per metre of thickness,
  // Neo-Hookean E = 50 kPa, nu = 0.3) pushed at its right end by nodal forces of 180 N along x and
  // 45 N along y for 0.3 s (3921 J of work), then free. At dt = 0.02 s the energy-momentum step
  // at t = 0.62 s finds no correction that keeps its cells valid: the run stops (exit 3) naming the
  // step and telling the user to take a smaller dt. At dt = 0.01 s it runs to the end, and after
  // the pulse the total energy is constant to 1e-9 relative (measured 1e-13; Newton's tolerance
  // is 1e-10 of the step's forces).
  const std::string text = R"J({"name": "pulse_bar",
    "settings": {"solver": "fem", "dt": 0.02, "duration": 2, "integrator": "energy_momentum", "gravity": [0, 0, 0]},
    "objects": [{"name": "bar", "kind": "solid", "mesh": {"type": "rectangle", "min": [0, 0], "max": [1, 0.1], "cells": [40, 4]},
                "material": {"model": "neo_hookean", "youngs_modulus": 5e4, "poisson_ratio": 0.3, "density": 100},
                "loads": [{"type": "nodal_force", "where": {"boundary": "right"}, "value": ["180*(t<0.3)", "45*(t<0.3)"]}]}],
    "probes": [{"name": "E", "type": "energy", "quantity": "total"}]})J";
  const std::string scene = write_scene("pulse_bar", text);
  const std::string dir = fs::path(scene).parent_path();
  const auto coarse = test::run_moreau(fmt::format("run {} --out {}/coarse --quiet", scene, dir));
  EXPECT_EQ(coarse.exit_code, 3) << coarse.output;
  EXPECT_NE(coarse.output.find("step 32 "), std::string::npos) << coarse.output;
  EXPECT_NE(coarse.output.find("a smaller settings.dt"), std::string::npos) << coarse.output;
  const auto rows = run_scene(scene, dir + "/fine", "--set settings.dt=0.01");
  ASSERT_EQ(rows.size(), 201u);
  Real reference = 0, drift = 0;
  for (const auto& row : rows) {
    if (row[0] < 0.3 + 1e-9) continue;
    if (reference == 0) reference = row[1];
    drift = std::max(drift, std::abs(row[1] - reference));
  }
  EXPECT_GT(reference, 1000.0);  // the pulse did its work
  EXPECT_LT(drift, 1e-9 * reference);
}

TEST(FemScenes, ResultsAreBitIdenticalOnOneAndTwoThreads) {
  // Cells are assembled colour by colour, so every global entry sums its cells in the same order
  // whatever the thread count; the factorization is serial. probes.csv must match byte for byte.
  const std::string scene = write_scene("fem_threads", R"J({"name": "twist",
    "settings": {"solver": "fem", "dt": 0.01, "duration": 0.2, "integrator": "energy_momentum", "gravity": [0, -9.81, 0],
                 "output": {"formats": []}},
    "objects": [{"name": "block", "kind": "solid", "mesh": {"type": "box", "min": [0, 0, 0], "max": [0.4, 0.2, 0.2], "cells": [8, 4, 4], "element": "tet4"},
                "material": {"youngs_modulus": 1e5, "poisson_ratio": 0.3, "density": 1000}, "velocity": [0, 0, 0],
                "dirichlet": [{"where": {"boundary": "left"}, "value": ["0", "0.05*sin(10*t)", "0"]}]}],
    "probes": [{"name": "tip", "type": "point", "object": "block", "nearest": [0.4, 0.2, 0.2]},
               {"name": "E", "type": "energy"}]})J");
  std::string csv[2];
  for (int threads : {1, 2}) {
    const std::string out = fs::path(scene).parent_path() / fmt::format("out{}", threads);
    const auto r = test::run_moreau(fmt::format("run {} --out {} --quiet --threads {}", scene, out, threads));
    ASSERT_EQ(r.exit_code, 0) << r.output;
    std::ifstream in(out + "/probes.csv");
    csv[threads - 1].assign((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  }
  EXPECT_GT(csv[0].size(), 500u);
  EXPECT_EQ(csv[0], csv[1]);
}

TEST(FemScenes, RigidBodyShowcaseFlipsWithEnergyAndOrthonormalityKept) {
  // scenes/fem_dzhanibekov.json: the director body of a 1 x 0.5 x 0.2 m box mesh, spun about its
  // intermediate axis. Its mesh gives the box's exact Euler tensor, so the first flip (the sign
  // change of the body-frame w_d2) comes at 2.97 s as in the director-body test against Euler's
  // equations (probes every 0.05 s: between 2.95 and 3.0 s); kinetic energy constant to 1e-11,
  // directors orthonormal to 1e-10.
  const std::string scene = (fs::path(MOREAU_SOURCE_DIR) / "scenes" / "fem_dzhanibekov.json").string();
  const std::string out = test::temp_dir("fem_dzhanibekov") + "/out";
  const auto rows = run_scene(scene, out, "--duration 4");
  ASSERT_GT(rows.size(), 50u);
  Real flip = -1, energy_drift = 0, orthonormality = 0;
  for (size_t k = 1; k < rows.size(); ++k) {
    if (flip < 0 && (rows[k][2] > 0) != (rows[k - 1][2] > 0)) flip = rows[k][0];
    energy_drift = std::max(energy_drift, std::abs(rows[k][4] - rows[0][4]) / rows[0][4]);
    orthonormality = std::max(orthonormality, rows[k][8]);
  }
  EXPECT_GT(flip, 2.95);
  EXPECT_LE(flip, 3.0 + 1e-9);
  EXPECT_LT(energy_drift, 1e-11);
  EXPECT_LT(orthonormality, 1e-10);
  EXPECT_TRUE(fs::exists(out + "/frames/box_000000.vtu"));
}

TEST(FemScenes, HingedBeamShowcaseKeepsEnergyAndJoints) {
  // scenes/fem_hinged_beam.json for 1 s: a 3.3 kg rubber beam hinged to a hub that turns on an
  // axle. The total energy with gravity's potential (scale m g L/2 ~ 10 J) stays constant to
  // 1e-8 J, the joints hold to 1e-10, and the hub turns about the axle (z) only.
  const std::string scene = (fs::path(MOREAU_SOURCE_DIR) / "scenes" / "fem_hinged_beam.json").string();
  const std::string out = test::temp_dir("fem_hinged") + "/out";
  const auto rows = run_scene(scene, out, "--duration 1");
  ASSERT_EQ(rows.size(), 51u);
  Real drift = 0, joints = 0, wobble = 0, spin = 0, drop = 0;
  for (const auto& row : rows) {
    drift = std::max(drift, std::abs(row[1] - rows[0][1]));
    joints = std::max(joints, row[8]);
    wobble = std::max({wobble, std::abs(row[5]), std::abs(row[6])});
    spin = std::max(spin, std::abs(row[7]));
    drop = std::max(drop, -row[3]);
  }
  EXPECT_LT(drift, 1e-8);
  EXPECT_LT(joints, 1e-10);
  EXPECT_LT(wobble, 1e-9);
  EXPECT_GT(spin, 1.0);  // the hub is dragged round
  EXPECT_GT(drop, 0.3);  // the beam swung down
}

TEST(FemScenes, BadInputNamesItsKey) {
  auto scene = [](const std::string& solid_extra, const std::string& settings_extra = "") {
    return R"({"name": "f", "settings": {"solver": "fem")" + settings_extra + R"(},
      "objects": [{"name": "s", "kind": "solid", "mesh": {"type": "box", "min": [0, 0, 0], "max": [1, 1, 1], "cells": [2, 2, 2]},
                  "material": {"youngs_modulus": 1e5, "poisson_ratio": 0.3, "density": 1000})" +
           solid_extra + "}]}";
  };
  const auto expect_bad = test::expect_bad_scene;
  expect_bad("fem_boundary", scene(R"(, "dirichlet": [{"where": {"boundary": "side"}, "value": [0, 0, 0]}])"),
             {"objects[0].dirichlet[0].where.boundary", "'side'", "left"});
  expect_bad("fem_expression", scene(R"(, "loads": [{"type": "nodal_force", "where": {"boundary": "top"}, "value": [0, "sin(", 0]}])"),
             {"objects[0].loads[0].value", "not a valid expression"});
  expect_bad("fem_components", scene(R"(, "loads": [{"type": "nodal_force", "where": {"boundary": "top"}, "value": [0, 1]}])"),
             {"objects[0].loads[0].value", "3 entries"});
  expect_bad("fem_traction", scene(R"(, "loads": [{"type": "traction", "where": {"box": {"min": [0, 0, 0], "max": [1, 1, 1]}}, "value": [0, 1, 0]}])"),
             {"objects[0].loads[0].where", "named boundary"});
  expect_bad("fem_static", scene("", R"(, "integrator": "static")"), {"Dirichlet", "rigid motion"});
  expect_bad("fem_material", scene(R"(, "dirichlet": [])").replace(scene("").find("\"youngs_modulus\""), 0, "\"lame_mu\": 1, "),
             {"objects[0].material", "either"});
  expect_bad("fem_integrator", scene("", R"(, "integrator": "rk4")"), {"settings.integrator", "energy_momentum"});
  expect_bad("fem_formulation", scene(R"(, "formulation": "mixed")"), {"objects[0].formulation", "mean_dilatation"});
  expect_bad("fem_formulation_material",
             scene(R"(, "formulation": "mean_dilatation")").replace(scene("").find("\"youngs_modulus\""), 0,
                                                                  "\"model\": \"st_venant_kirchhoff\", "),
             {"objects[0].formulation", "neo_hookean"});
  expect_bad("fem_formulation_cells",
             scene(R"(, "formulation": "mean_dilatation")").replace(scene("").find("\"cells\""), 0, "\"element\": \"tet4\", "),
             {"objects[0].formulation", "quad4 or hex8", "tet4"});
  expect_bad("fem_linear_solver", scene("", R"(, "linear_solver": {"type": "gmres"})"),
             {"settings.linear_solver.type", "direct, petsc"});
  expect_bad("fem_linear_solver_key", scene("", R"(, "linear_solver": {"tolerance": 1e-6})"),
             {"settings.linear_solver.tolerance", "\"type\": \"petsc\""});
  const std::string body = R"({"name": "f", "settings": {"solver": "fem", "integrator": "static"},
      "objects": [{"name": "b", "kind": "rigid_body", "mesh": {"type": "box", "min": [0, 0, 0], "max": [1, 1, 1], "cells": [1, 1, 1]}, "density": 1000}]})";
  expect_bad("fem_rigid_static", body, {"objects[0].kind", "dynamic integrator"});
  const std::string joint = R"({"name": "f", "settings": {"solver": "fem"},
      "objects": [{"name": "b", "kind": "rigid_body", "mesh": {"type": "box", "min": [0, 0, 0], "max": [1, 1, 1], "cells": [1, 1, 1]}, "density": 1000}],
      "joints": [{"name": "j", "type": "spherical", "bodies": ["b", "nowhere"], "anchor": [0, 0, 0]}]})";
  expect_bad("fem_joint_end", joint, {"joints[0].bodies", "'nowhere'"});
  // One vocabulary with the constraint engine: its kinds are named as such, the old FEM lists
  // point at "objects", and a joint is a "hinge" in both engines.
  expect_bad("fem_cloth", scene("").replace(scene("").find("\"kind\": \"solid\""), 15, "\"kind\": \"cloth\""),
             {"objects[0].kind", "'cloth'", "constraint engine"});
  expect_bad("fem_old_solids", R"({"name": "f", "settings": {"solver": "fem"}, "solids": []})", {"solids", "\"objects\""});
  expect_bad("fem_revolute", std::string(joint).replace(joint.find("\"spherical\""), 11, "\"revolute\""),
             {"joints[0].type", "'revolute'", "hinge"});
  expect_bad("fem_old_body_probe", scene("").replace(scene("").rfind("}"), 0, R"(, "probes": [{"name": "p", "type": "body", "object": "s"}])"),
             {"probes[0].type", "'body'", "angular_velocity"});
  expect_bad("fem_same_name", scene(R"(}, {"name": "s", "kind": "rigid_body", "mesh": {"type": "box", "min": [0, 0, 0], "max": [1, 1, 1], "cells": [1, 1, 1]}, "density": 1)"),
             {"objects[1].name", "'s'"});
}

}  // namespace
}  // namespace moreau
