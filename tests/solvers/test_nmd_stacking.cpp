// Resting contact under the velocity-level formulation: a column of boxes settles by the contact
// compliance's law and stays where it settles.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "moreau/solvers/nmd/nmd_assembly.hpp"
#include "moreau/solvers/nmd/projected_gauss_seidel.hpp"
#include "moreau/world.hpp"
#include "test_helpers.hpp"

namespace moreau {
namespace {

using test::run_steps;
using test::scene_from_json;

// A column of n unit cubes of 1000 kg on a plane, mu = 0.5, 60 Hz, default NMD settings.
Scene box_column(int n) {
  std::string boxes;
  for (int i = 0; i < n; ++i)
    boxes += fmt::format(R"(, {{"name": "box{}", "kind": "rigid_body", "shape": {{"type": "box", "half_extents": [0.5, 0.5, 0.5]}},
                            "position": [0, {}, 0], "density": 1000, "friction": 0.5}})",
                         i, 0.5 + i);
  return scene_from_json(fmt::format(R"({{"name": "column", "settings": {{"solver": "nmd"}},
    "objects": [{{"name": "ground", "kind": "collider", "shape": {{"type": "plane"}}, "friction": 0.5}}{}]}})",
                                     boxes));
}

TEST(NmdStacking, ColumnOfTenBoxesSettlesByTheContactComplianceAndStays) {
  // At rest a SPOOK contact row holds S l = -a C, i.e. C = -eps F: each of the four corner points
  // under box k (counted from the top, k = 1..10) carries k m g / 4 and sinks eps k m g / 4, so the
  // top box settles by eps m g (1 + ... + 10) / 4 = 55 eps m g / 4 (1.349 cm at the default
  // eps = 1e-7 m/N). Tolerance 1 % for what 50 Gauss-Seidel sweeps leave unconverged. Sideways it
  // must stay within 1 mm and no box may move faster than 1 cm/s (a column at rest; measured
  // 0.4 mm and 0.7 mm/s): with rigid contacts (eps = 0) the same column rocked itself into a
  // 0.3 m/s jitter, because four redundant points per face leave Gauss-Seidel a direction it does
  // not converge in, and friction coupled to it.
  const int n = 10;
  Scene s = box_column(n);
  const Real eps = s.model.settings.nmd.contact_compliance, m = 1000, g = 9.81;
  const Index top = s.model.objects[s.model.find_object("box9")].body;
  run_steps(s, 300);
  const Vec3 x = s.state.rigid.position[top];
  const Real settled = n - 0.5 - x.y(), expected = 55 * eps * m * g / 4;
  EXPECT_NEAR(settled, expected, 0.01 * expected);
  Real sideways = 0, fastest = 0;
  for (int i = 0; i < n; ++i) {
    const Index b = s.model.objects[s.model.find_object(fmt::format("box{}", i))].body;
    sideways = std::max(sideways, std::hypot(s.state.rigid.position[b].x(), s.state.rigid.position[b].z()));
    fastest = std::max(fastest, s.state.rigid.velocity[b].norm());
  }
  EXPECT_LT(sideways, 1e-3);
  EXPECT_LT(fastest, 1e-2);
  std::printf("nmd column of 10 boxes, 5 s: top settled %.5f m (eps F law %.5f m), sideways %.1e m, fastest %.1e m/s\n",
              settled, expected, sideways, fastest);
}

// 144 towers of two 0.4 m boxes on a plane, the top boxes thrown sideways at different speeds
// (all but one slide a few centimetres on their lower box and stop), 60 steps under pgs: the sweep splits the ground contacts (one
// level) and the box-on-box contacts (the next) between threads, and the result must be the same
// bits on one thread and on two (sweep_schedule.hpp: the same operations in the same order).
std::string towers(int threads) {
  std::string boxes;
  for (int i = 0; i < 12; ++i)
    for (int k = 0; k < 12; ++k) {
      const double x = 1.0 * i, z = 1.0 * k;
      boxes += fmt::format(R"(, {{"name": "low{}_{}", "kind": "rigid_body", "shape": {{"type": "box", "half_extents": [0.2, 0.2, 0.2]}},
                              "position": [{}, 0.2, {}], "density": 500, "friction": 0.4}})",
                           i, k, x, z);
      boxes += fmt::format(R"(, {{"name": "top{}_{}", "kind": "rigid_body", "shape": {{"type": "box", "half_extents": [0.2, 0.2, 0.2]}},
                              "position": [{}, 0.6, {}], "velocity": [{}, 0, {}], "density": 500, "friction": 0.4}})",
                           i, k, x, z, 0.05 * i, 0.04 * k);
    }
  return fmt::format(R"({{"name": "towers", "settings": {{"solver": "nmd", "threads": {}}},
    "objects": [{{"name": "ground", "kind": "collider", "shape": {{"type": "plane"}}, "friction": 0.4}}{}]}})",
                     threads, boxes);
}

std::vector<double> towers_after_one_second(int threads) {
  World world = World::from_json(towers(threads));
  for (int s = 0; s < 60; ++s) world.step();
  std::vector<double> out;
  for (const char* name : {"body.position", "body.orientation", "body.velocity", "body.angular_velocity"}) {
    const StateArray a = world.array(name);
    out.insert(out.end(), a.values.begin(), a.values.end());
  }
  return out;
}

TEST(NmdStacking, SweepsSharedBetweenThreadsGiveTheSerialBits) {
  {  // The towers' system is one the sweep splits: 144 ground manifolds, then 144 box-on-box ones.
    Scene scene = scene_from_json(towers(2));
    run_steps(scene, 1);
    VelocitySpace space;
    space.gather(scene.model, scene.state);
    NmdSystem system;
    NmdRowMemory memory;
    const Real h = scene.model.settings.dt;
    assemble_nmd_system(scene.model, scene.state, space, h, scene.state.time + h, system, memory);
    SweepSchedule schedule;
    schedule.build(system, static_cast<Index>(space.v.size()));
    EXPECT_EQ(schedule.tasks(), 288);
    EXPECT_EQ(schedule.levels(), 2);
    EXPECT_EQ(sweep_threads(schedule, 2), 2);
  }
  const std::vector<double> one = towers_after_one_second(1), two = towers_after_one_second(2);
  ASSERT_EQ(one.size(), two.size());
  long differing = 0;
  for (size_t i = 0; i < one.size(); ++i) differing += one[i] != two[i];
  EXPECT_EQ(differing, 0) << "of " << one.size() << " state values";
  // And the physics: the fastest top box (tower 11, 11; body 287) slides on its lower box at
  // 0.704 m/s against mu g until it stops. With v+ = v - n mu g h after n steps and x+ = x + h v+,
  // it covers h sum_n max(v0 - n mu g h, 0), 5.74 cm (v0^2 / (2 mu g) = 6.32 cm less about
  // v0 h / 2). Tolerance 3 %: the lower box gives a little under the top box's drag.
  const double h = 1.0 / 60, v0 = std::hypot(0.55, 0.44), decel = 0.4 * 9.81;
  double expected = 0;
  for (int n = 1; v0 - n * decel * h > 0; ++n) expected += h * (v0 - n * decel * h);
  const double slid = std::hypot(one[3 * 287] - 11, one[3 * 287 + 2] - 11);
  fmt::print("top box slid {:.4f} m (discrete Coulomb law {:.4f} m)\n", slid, expected);
  EXPECT_NEAR(slid, expected, 0.03 * expected);
}

}  // namespace
}  // namespace moreau
