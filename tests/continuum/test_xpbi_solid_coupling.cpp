// XPBI continua against cloth and DEM grains in the same substep: their particles meet in the
// particle contacts of every XPBD solve, so what one gives the other takes. Checked by what holds
// exactly: momentum in collisions without gravity, and the tensor virial of a slab carrying grains.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "moreau/model/diagnostics.hpp"
#include "moreau/scene/scene.hpp"
#include "continuum_test_helpers.hpp"
#include "test_helpers.hpp"

namespace moreau {
namespace {

void run(Scene& scene, Real duration) { test::run_steps(scene, std::lround(duration / scene.model.settings.dt)); }

Real object_mass(const Scene& scene, Index object) {
  Real mass = 0;
  for (Index p = scene.model.objects[object].particle_begin; p < scene.model.objects[object].particle_end; ++p)
    mass += scene.model.particle_mass[p];
  return mass;
}

// An elastic block 6 cm across (216 particles, 0.216 kg) moving down at 1 m/s onto `target`,
// without gravity.
Scene block_striking(const std::string& target) {
  return load_scene_text(fmt::format(R"({{"name": "strike", "settings": {{"solver": "xpbi", "dt": 0.005, "substeps": 10,
      "iterations": 5, "gravity": [0, 0, 0]}},
      "objects": [{{"name": "block", "kind": "continuum", "blocks": [{{"min": [-0.03, 0.02, -0.03], "max": [0.03, 0.08, 0.03]}}],
                    "spacing": 0.01, "density": 1000, "youngs_modulus": 1e5, "poisson_ratio": 0.3, "velocity": [0, -1, 0]}},
                   {}]}})",
                                     target),
                         "strike");
}

// Every contact's two impulses are equal and opposite, so the block and what it strikes keep
// their total momentum; 1e-12 of it is round-off over 600 substeps.
void expect_momentum_kept(const Scene& scene, const Vec3& before, const char* what) {
  const Vec3 after = linear_momentum(scene.model, scene.state, 0) + linear_momentum(scene.model, scene.state, 1);
  fmt::print("{}: momentum change {:.3g} of {:.4g} kg m/s\n", what, (after - before).norm(), before.norm());
  EXPECT_LT((after - before).norm(), 1e-12 * before.norm()) << what;
}

// A free cloth sheet 16 cm square (5.1 g) in the block's way. The sheet is driven ahead: it ends
// moving down at least as fast as the block, below every particle of the block (the block does
// not pass through it; the stretched sheet springs off its face).
TEST(XpbiSolidCoupling, ABlockStrikingAFreeSheetKeepsTheMomentumAndDrivesTheSheetAhead) {
  Scene scene = block_striking(R"({"name": "sheet", "kind": "cloth",
      "mesh": {"type": "grid", "size": [0.16, 0.16], "resolution": [17, 17], "center": [0, 0, 0]},
      "material": {"area_density": 0.2, "stretch_compliance": 1e-4, "bending_stiffness": 1e-5}})");
  const Vec3 before = linear_momentum(scene.model, scene.state, 0);
  run(scene, 0.3);
  expect_momentum_kept(scene, before, "block on a free sheet");
  const Real block_speed = -linear_momentum(scene.model, scene.state, 0).y() / object_mass(scene, 0);
  const Real sheet_speed = -linear_momentum(scene.model, scene.state, 1).y() / object_mass(scene, 1);
  Real block_bottom = 1e9, sheet_top = -1e9;
  for (Index p = scene.model.objects[0].particle_begin; p < scene.model.objects[0].particle_end; ++p)
    block_bottom = std::min(block_bottom, scene.state.position[p].y());
  for (Index p = scene.model.objects[1].particle_begin; p < scene.model.objects[1].particle_end; ++p)
    sheet_top = std::max(sheet_top, scene.state.position[p].y());
  fmt::print("after 0.3 s: block {:.4f} m/s, sheet {:.4f} m/s; sheet's top {:.4f} m below the block's bottom\n",
             block_speed, sheet_speed, block_bottom - sheet_top);
  EXPECT_GE(sheet_speed, block_speed);
  EXPECT_GT(block_bottom, sheet_top);
}

// A loose cluster of 98 grains (r = 5 mm, 0.133 kg) in the block's way. The grains are pushed
// ahead of the block; without restitution the collision is inelastic, so the block ends at the
// common speed of the two, P / (m_block + m_grains) = 0.619 m/s; 2 % for the grains at the
// cluster's edges, which the block does not strike head-on.
TEST(XpbiSolidCoupling, ABlockStrikingGrainsKeepsTheMomentumAndSharesIt) {
  Scene scene = block_striking(R"({"name": "grains", "kind": "granular", "blocks": [{"min": [-0.04, -0.03, -0.04],
      "max": [0.04, 0.0, 0.04]}], "radius": 0.005, "density": 2600, "friction": 0.5})");
  const Vec3 before = linear_momentum(scene.model, scene.state, 0);
  run(scene, 0.3);
  expect_momentum_kept(scene, before, "block on grains");
  const Real common = before.norm() / (object_mass(scene, 0) + object_mass(scene, 1));
  const Real block_speed = -linear_momentum(scene.model, scene.state, 0).y() / object_mass(scene, 0);
  fmt::print("after 0.3 s: block {:.4f} m/s, common speed {:.4f} m/s\n", block_speed, common);
  EXPECT_NEAR(block_speed, common, 0.02 * common);
}

// A layer of 25 grains (r = 6 mm) resting on an elastic slab on the ground. The slab's tensor
// virial at rest counts every external force at the particle it acts on: gravity at the centre
// of mass, the ground's reaction at the bottom particles' centres (r/2 up), the grains' weight at
// the top particles' centres, y_t:
//   int sigma_yy dV = -W_slab (y_c - r/2) - W_grains (y_t - r/2).
// The grains' part is a quarter of the whole, so a slab that did not carry them would miss by 23 %.
// 2 %: the bound of the continuum's own virial tests (surface particles' one-sided gradients).
TEST(XpbiSolidCoupling, GrainsRestingOnASlabAreCarriedByItsStress) {
  Scene scene = load_scene_text(R"({"name": "loaded", "settings": {"solver": "xpbi", "dt": 0.005, "substeps": 10, "iterations": 5},
      "objects": [{"name": "ground", "kind": "collider", "shape": {"type": "plane"}, "friction": 0.5},
                  {"name": "slab", "kind": "continuum", "blocks": [{"min": [-0.05, 0, -0.05], "max": [0.05, 0.04, 0.05]}],
                   "spacing": 0.01, "density": 1000, "youngs_modulus": 1e5, "poisson_ratio": 0.3, "friction": 0.5},
                  {"name": "grains", "kind": "granular", "blocks": [{"min": [-0.036, 0.0405, -0.036], "max": [0.036, 0.0526, 0.036]}],
                   "radius": 0.006, "density": 2600, "friction": 0.5}]})",
                                "loaded");
  run(scene, 1.0);
  const Real g = 9.81, r = scene.model.continuum.spacing;
  const Real slab_weight = g * object_mass(scene, 1), grain_weight = g * object_mass(scene, 2);
  Real top = -1e9;
  for (Index p : scene.model.continuum.particle) top = std::max(top, scene.state.position[p].y());
  Real top_layer = 0;
  int top_count = 0;
  for (Index p : scene.model.continuum.particle) {
    if (scene.state.position[p].y() < top - r / 2) continue;
    top_layer += scene.state.position[p].y();
    ++top_count;
  }
  top_layer /= top_count;
  const Real y_c = center_of_mass(scene.model, scene.state, 1).y();
  const Real expected = -slab_weight * (y_c - r / 2) - grain_weight * (top_layer - r / 2);
  const Real measured = test::continuum_stress_integral(scene)(1, 1);
  Real grains_on = 0;
  for (Index p = scene.model.objects[2].particle_begin; p < scene.model.objects[2].particle_end; ++p)
    grains_on += scene.state.position[p].y() > top;
  fmt::print("slab under grains: int sigma_yy dV = {:.6g} N m, expected {:.6g} N m ({:.3g} % of it the grains'), error {:.3g} %, "
             "{} of {} grains on top, kinetic {:.3g} J\n",
             measured, expected, 100 * grain_weight * (top_layer - r / 2) / -expected, 100 * (measured / expected - 1),
             grains_on, scene.model.objects[2].particle_end - scene.model.objects[2].particle_begin,
             kinetic_energy(scene.model, scene.state, -1));
  EXPECT_EQ(grains_on, scene.model.objects[2].particle_end - scene.model.objects[2].particle_begin);
  EXPECT_NEAR(measured / expected, 1, 0.02);
  EXPECT_LT(kinetic_energy(scene.model, scene.state, -1), 1e-8);  // at rest
}

}  // namespace
}  // namespace moreau
