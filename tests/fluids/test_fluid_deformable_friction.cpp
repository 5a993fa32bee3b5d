// The particle fluids' wall friction at cloth, soft bodies and continua (`fluid_friction` on a
// cloth, a soft body or a continuum, fluid_viscosity.hpp), under xpbd (a viscosity solve every
// substep) and nmd (one every step), and xpbi for the continuum: a pinned sheet holds start-up
// Couette flow as a still no-slip wall, and a free soft plate, sheet or continuum plate sliding
// along a viscous layer gives its momentum to the liquid and keeps the total. The
// gap, the liquid and the moving plate are those of the rigid-body tests
// (test_fluid_rigid_friction.cpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "moreau/model/diagnostics.hpp"
#include "fluid_test_helpers.hpp"
#include "test_helpers.hpp"

namespace moreau {
namespace {

using test::run_steps;
using test::scene_from_json;

constexpr Real kGap = 0.04;  // m: the liquid's lattice spans x in [0, H]
constexpr Real kDt = 1.0 / 120;
constexpr int kLayers = 10;  // lattice layers across the liquid
constexpr Real kU = 0.1;     // m/s, the moving plate's speed along y
constexpr Real kNu = 1e-2;   // m^2/s, mu = 10 Pa s at 1000 kg/m^3

// The liquid (r = 2 mm, mu = 10 Pa s, no gravity) in a tank, between `still` on the x < 0 side and
// `moving` on the x > H side, under `solver`.
std::string gap_scene(const std::string& solver, const std::string& still, const std::string& moving) {
  return R"({"name": "gap", "settings": {"solver": ")" + solver + R"(", "dt": 0.008333333333333333, "substeps": 10,
                  "gravity": [0, 0, 0]},
    "objects": [
      {"name": "box", "kind": "collider", "inside": true, "friction": 0,
       "shape": {"type": "box", "center": [0.02, 0.3, 0.012], "half_extents": [0.03, 0.4, 0.012]}},
      )" + still + ",\n" + moving + R"(,
      {"name": "liquid", "kind": "fluid", "particle_radius": 0.002, "viscosity": 10, "xsph": 0,
       "block": {"min": [0, 0.3, 0], "max": [0.04, 0.5, 0.024]}}]})";
}

// The still wall is a sheet pinned in the plane x = -r, where a collider's wall samples would lie
// (the liquid's first layer sits 2 r from it, at x = r), with no-slip fluid friction; the moving
// wall is the kinematic rigid plate of the rigid-body test, sliding along y at U with its no-slip
// surface at x = H. A sheet's samples are not extrapolated, so the liquid's velocity vanishes at
// the sheet itself, and the gap is H + r. Start-up Couette flow across it,
//   u(s, t) = U s / G - sum_n 2 U / (n pi) (-1)^(n+1) sin(n pi s / G) exp(-n^2 pi^2 nu t / G^2),
// s = x + r, G = H + r. At t = 0.1 s (6 diffusion times) the rigid and collider versions have every
// layer within 1.0 % and 0.3 % of U; the bound is theirs, 2 % of U (measured: 0.81 % under xpbd,
// 1.23 % under nmd). With the sheet free-slip ("fluid_friction": 0) the liquid slides along it: the
// worst layer is then 61 % of U off this profile (xpbd), and the test checks that it is off.
class DeformableFrictionOnEverySolver : public ::testing::TestWithParam<std::string> {};

// The worst layer's departure from that profile (a fraction of U) beside a sheet of this friction.
Real couette_departure_beside_a_sheet(const std::string& solver, const std::string& friction) {
  const Real r = 0.002;
  Scene scene = scene_from_json(gap_scene(solver,
      R"({"name": "sheet", "kind": "cloth", "fluid_friction": )" + friction + R"(,
          "mesh": {"type": "grid", "size": [0.5, 0.05], "resolution": [51, 6], "center": [-0.002, 0.3, 0.012],
                   "rotation_deg": [0, 0, 90]},
          "material": {"area_density": 0.2, "stretch_compliance": 0},
          "pin": [{"box": {"min": [-1, -1, -1], "max": [1, 1, 1]}}]})",
      R"({"name": "moving", "kind": "rigid_body", "kinematic": true, "fluid_friction": 1,
          "velocity": [0, 0.1, 0], "shape": {"type": "box", "half_extents": [0.005, 0.2, 0.03]},
          "position": [0.045, 0.4, 0.012]})"));
  run_steps(scene, 12);
  const Real t = 12 * kDt, gap = kGap + r;
  const test::SliceSpeeds layers = test::slice_speeds(scene.state.fluid, kGap, kLayers, 0.35, 0.45);
  Real worst = 0;
  for (int k = 0; k < kLayers; ++k) {
    EXPECT_GT(layers.count[k], 0) << "layer " << k;
    if (layers.count[k] == 0) return 1;  // an empty layer: no profile to compare
    const Real exact = test::couette_startup_speed(layers.x[k] + r, t, kU, gap, kNu);
    worst = std::max(worst, std::abs(layers.speed[k] - exact) / kU);
  }
  std::printf("%s: Couette beside a pinned sheet of fluid friction %s at t = %.3f s: worst layer %.2f %% of U (sheet "
              "layer %.4f, exact %.4f m/s)\n",
              solver.c_str(), friction.c_str(), t, 100 * worst, layers.speed[0],
              test::couette_startup_speed(layers.x[0] + r, t, kU, gap, kNu));
  return worst;
}

TEST_P(DeformableFrictionOnEverySolver, APinnedSheetHoldsCouetteFlowAsAStillWall) {
  EXPECT_LT(couette_departure_beside_a_sheet(GetParam(), "1"), 0.02);
  // The sheet's grip is what holds the profile: free-slip, the liquid slides along it (measured:
  // 61 % of U under xpbd).
  EXPECT_GT(couette_departure_beside_a_sheet(GetParam(), "0"), 0.2);
}

// A free soft plate of 0.2 kg (stiff Neo-Hookean tetrahedra, the rigid-body test's box) sliding
// along y at 0.1 m/s beside the 0.192 kg layer at rest, every other wall free-slip. Only the
// plate's fluid friction acts along y, so the liquid's and the plate's y momenta sum to the start's
// to the solve's residual (the rigid plate: 2.1e-4 of the start's), and liquid and plate end moving
// together at m U / (m + M). The soft plate's samples are not extrapolated through its surface, so
// the liquid slips by about r there and they get together more slowly than with the rigid plate
// (within 0.14 % after 0.5 s): the plate is still 0.72 % fast at 0.5 s and 0.04 % slow at 0.75 s
// (xpbd), hence 0.75 s (4.7 diffusion times H^2 / nu). The plate's surface layer, half its mass
// over its 0.3 x 0.022 m face (15 kg/m^2), outweighs the liquid it drags in a viscosity step,
// rho sqrt(nu h) = 2.9 kg/m^2 (xpbd's substep) and 9.1 kg/m^2 (nmd's step), so the explicit
// reaction is stable.
constexpr Real kPlateMass = 0.2;  // kg

// A free-slip still wall and the free `plate` sliding along y at U, under `solver`.
std::string free_plate_scene(const std::string& solver, const std::string& plate) {
  return gap_scene(solver,
                   R"({"name": "still", "kind": "collider", "shape": {"type": "box", "center": [-0.005, 0.3, 0.012],
                       "half_extents": [0.005, 0.4, 0.03]}})",
                   plate);
}

// The soft plate: stiff Neo-Hookean tetrahedra filling the rigid-body test's box.
std::string soft_plate(const std::string& solver) {
  const Real volume = 0.006 * 0.3 * 0.022;
  return free_plate_scene(solver, R"({"name": "plate", "kind": "soft_body", "fluid_friction": 1, "velocity": [0, 0.1, 0],
      "friction": 0, "mesh": {"type": "box", "min": [0.040, 0.25, 0.001], "max": [0.046, 0.55, 0.023], "cells": [1, 30, 2]},
      "material": {"youngs_modulus": 2e5, "poisson_ratio": 0.3, "density": )" + fmt::format("{}", kPlateMass / volume) + "}}");
}

// The sheet: an inextensible cloth of the same mass in the plate's liquid-side face, x = H + r, where
// the soft plate's samples lie (0.3 x 0.022 m, 30.3 kg/m^2). Its collider gap is 0: with the default
// (its collision radius, 4.5 mm, more than its 1 mm clearance from the tank's side walls) its
// edges are pressed into those walls and it crumples, and the y momentum then drifted by 1.2e-2 of
// the start's under xpbd (1.3e-4 with the sheet free-slip) and by 2.4e-2 under nmd even free-slip.
std::string free_sheet(const std::string& solver) {
  return free_plate_scene(solver, R"({"name": "plate", "kind": "cloth", "fluid_friction": 1, "velocity": [0, 0.1, 0],
      "friction": 0, "collider_gap": 0, "mesh": {"type": "grid", "size": [0.3, 0.022], "resolution": [31, 4], "center": [0.042, 0.4, 0.012],
                              "rotation_deg": [0, 0, 90]},
      "material": {"area_density": )" + fmt::format("{}", kPlateMass / (0.3 * 0.022)) + R"(, "stretch_compliance": 0}})");
}

// The plate's and the liquid's mean y velocities after `steps` steps, and the largest drift of the
// total y momentum from the start's, as a fraction of it.
struct SharedMomentum {
  Real plate_speed, liquid_speed, liquid_mass, worst_drift;
};

SharedMomentum share_momentum(Scene& scene, int steps) {
  const ObjectInfo& plate = scene.model.objects[scene.model.find_object("plate")];
  auto plate_momentum = [&] {
    Real momentum = 0;
    for (Index p = plate.particle_begin; p < plate.particle_end; ++p)
      momentum += scene.state.velocity[p].y() / scene.model.particle_inv_mass[p];
    return momentum;
  };
  Real liquid = 0;
  for (Index i = 0; i < scene.state.fluid.count; ++i) liquid += scene.state.fluid.mass[i];
  const Real p0 = linear_momentum(scene.model, scene.state, -1).y();
  EXPECT_NEAR(plate_momentum() / (kPlateMass * kU), 1, 1e-9);
  Real worst_drift = 0;
  for (int step = 0; step < steps; ++step) {
    run_steps(scene, 1);
    worst_drift = std::max(worst_drift, std::abs(linear_momentum(scene.model, scene.state, -1).y() - p0));
  }
  Real fluid_momentum = 0;
  for (Index i = 0; i < scene.state.fluid.count; ++i)
    fluid_momentum += scene.state.fluid.mass[i] * scene.state.fluid.velocity[i].y();
  return {plate_momentum() / kPlateMass, fluid_momentum / liquid, liquid, worst_drift / p0};
}

// After 0.75 s the plate (`label`) and the liquid move at m U / (m + M) within 1 % (as for the rigid
// plate: its slowest mode's 6e-4 at 0.5 s and the momentum's drift), and the y momentum stayed
// within 1e-3 of the start's (the solve's tolerance, 1e-4 of each substep's viscous impulse).
void expect_plate_and_liquid_share_momentum(Scene& scene, const std::string& label) {
  const SharedMomentum end = share_momentum(scene, 90);
  const Real together = kPlateMass * kU / (kPlateMass + end.liquid_mass);
  std::printf("%s after 0.75 s: plate %.5f, liquid %.5f m/s against m U / (m + M) = %.5f; y momentum drift at most "
              "%.2e of the start's\n",
              label.c_str(), end.plate_speed, end.liquid_speed, together, end.worst_drift);
  EXPECT_NEAR(end.plate_speed / together, 1, 0.01);
  EXPECT_NEAR(end.liquid_speed / together, 1, 0.01);
  EXPECT_LT(end.worst_drift, 1e-3);
}

TEST_P(DeformableFrictionOnEverySolver, AFreeSoftPlateDragsTheLiquidAlongAndKeepsTheMomentum) {
  Scene scene = scene_from_json(soft_plate(GetParam()));
  expect_plate_and_liquid_share_momentum(scene, GetParam() + ": free soft plate");
}

// The same with a free sheet of the plate's mass in place of the soft plate: the sheet's own wall
// velocity and reaction (its vertices are free). Its samples lie on the sheet, 2 r from the
// liquid's last layer, as the soft plate's lie r inside its face. Same bounds, same reasons.
TEST_P(DeformableFrictionOnEverySolver, AFreeSheetDragsTheLiquidAlongAndKeepsTheMomentum) {
  Scene scene = scene_from_json(free_sheet(GetParam()));
  expect_plate_and_liquid_share_momentum(scene, GetParam() + ": free sheet");
}

// The same with an elastic continuum plate of the plate's mass under xpbi: two layers of particles
// at the fluid's spacing 2 r, the first at x = H + r where the soft plate's samples lie (a
// continuum's samples are its particles). Its particles take the reaction as velocity, which the
// continuum's end of substep carries into their motion (x = x^n + h v). Same bounds, same reasons.
TEST(DeformableFriction, AFreeContinuumPlateDragsTheLiquidAlongAndKeepsTheMomentum) {
  const Real particles = 2 * 75 * 6, cell = 0.004 * 0.004 * 0.004;
  Scene scene = scene_from_json(free_plate_scene("xpbi", R"({"name": "plate", "kind": "continuum", "fluid_friction": 1,
      "velocity": [0, 0.1, 0], "friction": 0, "blocks": [{"min": [0.040, 0.25, 0], "max": [0.048, 0.55, 0.024]}],
      "spacing": 0.004, "youngs_modulus": 1e5, "density": )" + fmt::format("{}", kPlateMass / (particles * cell)) + "}"));
  expect_plate_and_liquid_share_momentum(scene, "xpbi: free continuum plate");
}

// The samples' wall velocities and the vertices' reactions are summed in fixed orders, so the run
// is bit-identical on one and two threads.
TEST(DeformableFriction, BitIdenticalForOneAndTwoThreads) {
  auto run = [](int threads) {
    Scene scene = scene_from_json(soft_plate("xpbd"), {fmt::format("settings.threads={}", threads)});
    run_steps(scene, 5);
    std::vector<Vec3> out = scene.state.velocity;
    for (const auto& [id, x] : test::by_particle_id(scene.state.fluid, scene.state.fluid.velocity)) out.push_back(x);
    return out;
  };
  const std::vector<Vec3> one = run(1), two = run(2);
  ASSERT_EQ(one.size(), two.size());
  for (std::size_t k = 0; k < one.size(); ++k) ASSERT_EQ(one[k], two[k]) << "entry " << k;
}

INSTANTIATE_TEST_SUITE_P(Solvers, DeformableFrictionOnEverySolver, ::testing::Values("xpbd", "nmd"));

}  // namespace
}  // namespace moreau
