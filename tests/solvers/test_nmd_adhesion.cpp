// Adhesive contact under "nmd" (Gascon, Zurdo, Otaduy 2010): a contact point may pull down to
// -A, its glue a spring of the contact compliance that lets go beyond.
#include <gtest/gtest.h>

#include <cstdio>

#include "test_helpers.hpp"

namespace moreau {
namespace {

using test::run_steps;
using test::scene_from_json;

// A 10 kg cube of 0.2 m stuck under a ceiling (the bottom face of a fixed box at y = 1 m) by the
// glue on its top face, adhesion A per contact point; 60 Hz, default settings.nmd.
Scene glued_cube(Real adhesion) {
  return scene_from_json(fmt::format(R"({{"name": "glue", "settings": {{"solver": "nmd", "dt": 0.016666666666666666}},
    "objects": [
      {{"name": "ceiling", "kind": "collider", "shape": {{"type": "box", "center": [0, 1.1, 0], "half_extents": [1, 0.1, 1]}}}},
      {{"name": "cube", "kind": "rigid_body", "shape": {{"type": "box", "half_extents": [0.1, 0.1, 0.1]}},
       "position": [0, 0.9, 0], "mass": 10, "adhesion": {}}}]}})",
                                     adhesion));
}

Real drop_after(Real adhesion, int steps) {
  Scene scene = glued_cube(adhesion);
  const Index body = scene.model.objects[scene.model.find_object("cube")].body;
  run_steps(scene, steps);
  return 0.9 - scene.state.rigid.position[body].y();
}

TEST(NmdAdhesion, GluedCubeHangsByItsContactSpring) {
  // The face-to-face manifold has four corner points sharing m g = 98.1 N by symmetry: each pulls
  // 24.525 N, and its spring (contact compliance 1e-7 m/N) stretches by eps m g / 4 = 2.4525e-6 m.
  // After 4 s (the hanging cube settles more slowly than a resting one: 0.5 % short after 1 s,
  // 4e-6 after 4 s); tolerance 1e-4 relative, as for the resting cube.
  const Real drop = drop_after(30, 240);
  std::printf("glued cube hangs %.6e m below the ceiling (eps m g / 4 = 2.4525e-06 m)\n", drop);
  EXPECT_NEAR(drop, 2.4525e-6, 1e-4 * 2.4525e-6);
}

TEST(NmdAdhesion, GlueHoldsExactlyUpToItsStrength) {
  // Held iff m g <= 4 A, A = 24.525 N: 25 N per point holds, 24 N lets go (2 % either side); let
  // go, the cube falls freely (g t^2 / 2 = 1.226 m after 0.5 s) but for the first step's pull
  // (bound 5 cm). Held, it hangs by its springs' stretch, 2.45e-6 m: the bound 1e-5 m leaves room
  // for the settling and is 5 orders below the fall.
  const Real held = drop_after(25, 30), released = drop_after(24, 30);
  std::printf("after 0.5 s: A = 25 N: %.3e m; A = 24 N: %.4f m (free fall 1.226 m)\n", held, released);
  EXPECT_LT(held, 1e-5);
  EXPECT_NEAR(released, 0.5 * 9.81 * 0.25, 0.05);
}

}  // namespace
}  // namespace moreau
