// A continuum in particle water under XPBI, coupled two-way through the fluid's density
// constraint: a light block floats at Archimedes' draft, a dense one sinks.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <algorithm>

#include "moreau/scene/scene.hpp"
#include "fluid_test_helpers.hpp"

namespace moreau {
namespace {

// An elastic continuum slab 12.5 x 6.25 x 12.5 cm (500 particles of spacing 12.5 mm, the water's
// particle spacing) dropped onto 0.1 m of water in the 0.24 m tank of the soft-slab test.
Scene slab_in_water(Real density) {
  return load_scene_text(test::slab_tank_scene(fmt::format(R"({{"name": "slab", "kind": "continuum",
      "blocks": [{{"min": [-0.0625, 0.102, -0.0625], "max": [0.0625, 0.1645, 0.0625]}}], "spacing": 0.0125,
      "density": {}, "youngs_modulus": 1e5, "poisson_ratio": 0.3}})",
                                                           density)),
                         "slab", {"settings.solver=xpbi"});
}

// The slab's bottom face: its lowest particle centre less half a spacing.
Real slab_bottom(const Scene& scene) {
  Real lowest = 1e9;
  for (Index p : scene.model.continuum.particle) lowest = std::min(lowest, scene.state.position[p].y());
  return lowest - scene.model.continuum.spacing / 2;
}

void run(Scene& scene, int steps) {
  StageTimer timer;
  for (int k = 0; k < steps; ++k) scene.formulation->step(scene.model, scene.state, timer, 1);
}

// Archimedes: rho_s H = rho_w T, T = 0.03125 m at half the water's density. The slab still bobs
// by about 2 mm after 1.2 s (the light water damps little), so the draft is its mean over the
// next 0.6 s. Tolerance r / 2 = 3.1 mm, as for the soft slab: the particle free surface settles
// about r / 2 below the lattice top.
TEST(XpbiFluidCoupling, ALightContinuumFloatsAtTheArchimedesDraft) {
  Scene scene = slab_in_water(500);
  run(scene, 300);
  Real draft = 0;
  const int samples = 150;
  for (int k = 0; k < samples; ++k) {
    run(scene, 1);
    draft += (test::slab_tank_open_surface(scene.state.fluid) - slab_bottom(scene)) / samples;
  }
  fmt::print("draft {:.4f} m (Archimedes: 0.5 x 0.0625 = 0.03125 m)\n", draft);
  EXPECT_NEAR(draft, 0.03125, 0.5 * 0.00625);
}

TEST(XpbiFluidCoupling, ADenseContinuumSinksToTheFloor) {
  Scene scene = slab_in_water(2000);
  run(scene, 300);
  fmt::print("bottom {:.4f} m after 1.2 s\n", slab_bottom(scene));
  EXPECT_LT(slab_bottom(scene), 0.0125);  // on the floor, under at most a layer of water
}

}  // namespace
}  // namespace moreau
