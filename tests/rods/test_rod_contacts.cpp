// Rods touch the ground, each other and rigid bodies as the chains of capsules they are: rods laid
// on the ground, a rod across them and a rod along a box come to rest at the heights their radii
// give, under both formulations.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <cmath>
#include <string>
#include <tuple>
#include <vector>

#include "moreau/math/types.hpp"
#include "moreau/world.hpp"

namespace moreau {
namespace {

// Two parallel rods (r = 1 cm, 1 m, 20 segments, E = 1 GPa) dropped from 2 cm onto the ground
// 0.6 m apart, a third dropped from 5 cm across them (its segment 4 centred over the left rod),
// and a fourth dropped from 5 cm along the top of a fixed box 0.2 m high and 1.2 m long. At rest
// after 2 s: the lower rods' centrelines at r, the crossing rod's at 3r where it lies on the left
// rod, the fourth's at 0.2 m + r. A fifth lies across a 0.4 m block, overhanging it unevenly:
// it stays where it fell, its middle on the block and its ends above it (the capsules over the
// block's edges once took contact normals tilted towards the block's centre, and such a rod
// perched 4.5 mm above the block or slid off along itself). Under xpbd the contact between two rods (Gauss-Seidel, after
// the rods' direct solve) and the rods meet only through the iterations: with one, the crossing
// rod rests 0.38 mm into the other; with four (here), 0.1 mm.
std::vector<double> rest_heights(const std::string& solver_settings, int steps) {
  const std::string rod = R"("kind": "rod", "segments": 20, "radius": 0.01, "youngs_modulus": 1e9, "density": 1000, "damping_time": 0.01, "friction": 0.6)";
  World w = World::from_json(fmt::format(
      R"({{"name": "pile", "settings": {{{}, "duration": 2}},
      "objects": [{{"name": "ground", "kind": "collider", "shape": {{"type": "plane"}}, "friction": 0.6}},
                  {{"name": "left", {}, "points": [[-0.3, 0.03, -0.5], [-0.3, 0.03, 0.5]]}},
                  {{"name": "right", {}, "points": [[0.3, 0.03, -0.5], [0.3, 0.03, 0.5]]}},
                  {{"name": "across", {}, "points": [[-0.525, 0.08, 0], [0.475, 0.08, 0]]}},
                  {{"name": "table", "kind": "rigid_body", "fixed": true, "shape": {{"type": "box", "size": [0.4, 0.2, 1.2]}}, "position": [2, 0.1, 0]}},
                  {{"name": "on_table", {}, "points": [[2, 0.25, -0.5], [2, 0.25, 0.5]]}},
                  {{"name": "block", "kind": "rigid_body", "fixed": true, "shape": {{"type": "box", "size": [0.4, 0.2, 0.4]}}, "position": [4, 0.1, 0]}},
                  {{"name": "overhanging", {}, "points": [[4, 0.25, -0.525], [4, 0.25, 0.475]]}}],
      "probes": [{{"name": "left", "type": "point", "object": "left", "vertex": 10}},
                 {{"name": "right", "type": "point", "object": "right", "vertex": 10}},
                 {{"name": "across4", "type": "point", "object": "across", "vertex": 4}},
                 {{"name": "across5", "type": "point", "object": "across", "vertex": 5}},
                 {{"name": "on_table", "type": "point", "object": "on_table", "vertex": 10}},
                 {{"name": "overhanging", "type": "point", "object": "overhanging", "vertex": 10}},
                 {{"name": "overhanging_end", "type": "point", "object": "overhanging", "vertex": 0}}]}})",
      solver_settings, rod, rod, rod, rod, rod));
  for (int s = 0; s < steps; ++s) w.step();
  const std::vector<double> v = w.probe_values();
  return {v[1], v[4], (v[7] + v[10]) / 2, v[13], v[16], v[17] + 0.025, v[19]};
}

TEST(RodContacts, RodsRestOnTheGroundOnEachOtherAndOnABox) {
  const Real r = 0.01;
  for (const auto& [name, settings, steps] : {std::tuple{"xpbd", R"("dt": 0.01, "substeps": 20, "iterations": 4)", 200},
                                              std::tuple{"nmd", R"("solver": "nmd", "dt": 0.005, "nmd": {"method": "direct"})", 400}}) {
    const std::vector<double> h = rest_heights(settings, steps);
    std::printf("rods at rest, %s: lower rods at %.5f and %.5f m (r = %.3f), the crossing rod at %.5f m (3r = %.3f), the rod on the box "
                "at %.5f m (0.2 + r = %.3f)\n",
                name, h[0], h[1], r, h[2], 3 * r, h[3], 0.2 + r);
    EXPECT_NEAR(h[0], r, 1e-4) << name;
    EXPECT_NEAR(h[1], r, 1e-4) << name;
    EXPECT_NEAR(h[2], 3 * r, 2e-4) << name;
    EXPECT_NEAR(h[3], 0.2 + r, 1e-4) << name;
    std::printf("rod across a 0.4 m block, overhanging 0.325 and 0.275 m, %s: middle at %.5f m (0.2 + r = %.3f), slid %.2e m "
                "along itself, far end at %.5f m\n",
                name, h[4], 0.2 + r, h[5], h[6]);
    EXPECT_NEAR(h[4], 0.2 + r, 5e-4) << name;  // the overhangs' moments may lift the middle a little
    EXPECT_LT(std::abs(h[5]), 1e-3) << name;
    EXPECT_GT(h[6], 0.2) << name;
  }
}

}  // namespace
}  // namespace moreau

namespace moreau {
namespace {

// A ring (a helix of one turn without pitch: its two ends meet) and a tight coil (pitch 1.5 r,
// so neighbouring turns touch) at rest without gravity stay still: capsules that touch in the
// rest shape do not collide, so nothing pushes them apart.
TEST(RodContacts, CapsulesTouchingInTheRestShapeDoNotPushEachOther) {
  for (const char* pitch : {"0", "0.015"}) {
    World w = World::from_json(fmt::format(
        R"({{"name": "ring", "settings": {{"dt": 0.01, "substeps": 10, "duration": 0.5, "gravity": [0, 0, 0]}},
        "objects": [{{"name": "ring", "kind": "rod", "helix": {{"radius": 0.1, "pitch": {}, "turns": 1.5}}, "segments": 48,
                      "radius": 0.01, "youngs_modulus": 1e8, "density": 1000}}],
        "probes": [{{"name": "moved", "type": "max_displacement", "object": "ring"}}]}})",
        pitch));
    for (int s = 0; s < 50; ++s) w.step();
    std::printf("rod coil, pitch %s m: largest displacement %.2e m after 0.5 s at rest\n", pitch, w.probe_values()[0]);
    EXPECT_LT(w.probe_values()[0], 1e-9) << pitch;
  }
}

}  // namespace
}  // namespace moreau

namespace moreau {
namespace {

// A rod hung by a spherical joint from a cloth's vertex: a 1 m square cloth (11 x 11 vertices,
// 0.1 kg each) pinned along its four edges like a trampoline, the rod (0.5 m, 10 segments,
// 0.39 kg) joined to its centre vertex. After 3 s the joint holds (gap below 1 mm), the rod hangs
// from that vertex 0.5 m long and within 5 mm of the vertical through it (what is left of its swing
// on the sheet under xpbd, whose sheet sags 6 cm; nmd's inextensible sheet stays flat), under both
// solvers. The hooked vertex does not collide with the rod's segment it holds (a joint's ends do
// not touch); before, it pushed the rod 6 cm away from the hook.
TEST(RodContacts, ARodHangsFromAClothVertex) {
  for (const std::string settings :
       {R"("dt": 0.005, "substeps": 20)", R"("solver": "nmd", "dt": 0.005, "nmd": {"method": "direct"})"}) {
    World w = World::from_json(fmt::format(
        R"({{"name": "hanger", "settings": {{{}, "duration": 3}},
        "objects": [{{"name": "sheet", "kind": "cloth", "mesh": {{"type": "grid", "size": [1, 1], "resolution": [11, 11], "center": [0, 1, 0]}},
                      "material": {{"vertex_mass": 0.1, "damping": 0.05}}, "self_collision": false, "collision_radius": 0.002,
                      "pin": [{{"box": {{"min": [-1, 0.9, -0.51], "max": [1, 1.1, -0.49]}}}}, {{"box": {{"min": [-1, 0.9, 0.49], "max": [1, 1.1, 0.51]}}}},
                              {{"box": {{"min": [-0.51, 0.9, -1], "max": [-0.49, 1.1, 1]}}}}, {{"box": {{"min": [0.49, 0.9, -1], "max": [0.51, 1.1, 1]}}}}]}},
                    {{"name": "rod", "kind": "rod", "points": [[0, 1, 0], [0, 0.5, 0]], "segments": 10, "radius": 0.005,
                      "youngs_modulus": 1e9, "density": 5000, "damping_time": 0.01}}],
        "joints": [{{"name": "hook", "type": "spherical", "bodies": [{{"object": "sheet", "nearest": [0, 1, 0]}}, {{"object": "rod", "vertex": 0}}]}}],
        "probes": [{{"name": "top", "type": "point", "object": "rod", "vertex": 0}},
                   {{"name": "tip", "type": "point", "object": "rod", "vertex": 10}},
                   {{"name": "vertex", "type": "point", "object": "sheet", "nearest": [0, 1, 0]}},
                   {{"name": "hook", "type": "joint_error", "joint": "hook"}}]}})",
        settings));
    while (w.time() < 3 - 1e-9) w.step();
    const std::vector<double> v = w.probe_values();
    const Vec3 top(v[0], v[1], v[2]), tip(v[3], v[4], v[5]), vertex(v[6], v[7], v[8]);
    std::printf("rod hung from a cloth vertex (%s): vertex at (%.4f, %.4f, %.4f) m, tip %.5f m below it, off the vertical "
                "by %.2e m, hook gap %.2e m\n",
                settings.substr(0, 20).c_str(), vertex.x(), vertex.y(), vertex.z(), vertex.y() - tip.y(),
                std::hypot(tip.x() - vertex.x(), tip.z() - vertex.z()), v[9]);
    EXPECT_LT(v[9], 1e-3) << settings;
    EXPECT_LT((top - vertex).norm(), 1e-3) << settings;
    EXPECT_LT(std::hypot(tip.x() - vertex.x(), tip.z() - vertex.z()), 5e-3) << settings;
    EXPECT_NEAR(vertex.y() - tip.y(), 0.5, 1e-3) << settings;
  }
}

}  // namespace
}  // namespace moreau
