// Soft-body physics against analytic values.
#include <gtest/gtest.h>

#include "moreau/model/diagnostics.hpp"
#include "test_helpers.hpp"

using namespace moreau;

namespace {

// A bar of length L = 1 m and cross-section 0.1 x 0.1 m hanging from its top face, nu = 0 so the
// top pin does not restrain a lateral contraction. Linear elasticity: the bottom end moves down by
// rho g L^2 / (2E) = 1000 * 9.81 / (2e6) = 4.905 mm (strain 0.5 %).
Real hanging_bar_stretch(int iterations) {
  Scene s = test::scene_from_json(fmt::format(R"({{"name": "bar", "settings": {{"dt": 0.0050625, "substeps": 50,
      "iterations": {}, "gravity": [0, -9.81, 0]}},
    "objects": [{{"name": "bar", "kind": "soft_body",
      "mesh": {{"type": "box", "min": [0, -1, 0], "max": [0.1, 0, 0.1], "cells": [2, 20, 2]}},
      "material": {{"youngs_modulus": 1e6, "poisson_ratio": 0.0, "density": 1000}},
      "pin": [{{"box": {{"min": [-1, -0.001, -1], "max": [1, 1, 1]}}}}]}}]}})",
                                              iterations));
  // Released from rest, the undamped bar oscillates about its static equilibrium. The axial modes
  // of a fixed-free bar have periods T1/(2n-1) with T1 = 4L/sqrt(E/rho) = 0.1265 s, so the time
  // average over exactly 10 T1 (250 steps of 5.0625 ms) is the static elongation. (Damping would
  // settle it too, but XPBD damping with one iteration inflates the static compliance by
  // (1 + tau/h), which is what this test must not hide.)
  const Model& m = s.model;
  Real sum = 0;
  long samples = 0;
  StageTimer timer;
  for (int step = 0; step < 250; ++step) {
    s.formulation->step(s.model, s.state, timer, solver_thread_count(s.model));
    for (Index p = 0; p < m.particle_count(); ++p)
      if (m.particle_rest_position[p].y() < -0.999) {
        sum += s.state.position[p].y() - m.particle_rest_position[p].y();
        ++samples;
      }
  }
  return -sum / samples;
}

}  // namespace

TEST(SoftBodyValidation, HangingBarStretchesByRhoGLSquaredOverTwoE) {
  const Real expected = 1000 * 9.81 * 1.0 / (2 * 1e6);
  const Real one = hanging_bar_stretch(1);
  const Real ten = hanging_bar_stretch(10);
  fmt::print("hanging bar: expected {:.4f} mm, 1 iteration {:.4f} mm, 10 iterations {:.4f} mm\n", expected * 1e3, one * 1e3,
             ten * 1e3);
  // 3 %: lumped masses on 20 elements along the bar (O(1/n^2) = 0.25 %), finite strain (0.5 %),
  // the time average over a finite window (about 0.5 %), and the XPBD solve that is not converged
  // within a substep, whose added compliance scales with h^2.
  EXPECT_NEAR(one, expected, 0.03 * expected);
  EXPECT_NEAR(ten, expected, 0.03 * expected);
  // XPBD's promise: the stiffness does not depend on the iteration count (PBD's does).
  EXPECT_NEAR(one, ten, 0.03 * expected);
}

TEST(SoftBodyValidation, SquashedBlockRecoversItsRestVolume) {
  Scene s = test::scene_from_json(R"({"name": "squash", "settings": {"dt": 0.005, "substeps": 20, "gravity": [0, 0, 0]},
    "objects": [{"name": "b", "kind": "soft_body",
      "mesh": {"type": "box", "min": [0, 0, 0], "max": [0.2, 0.2, 0.2], "cells": [4, 4, 4]},
      "material": {"youngs_modulus": 1e5, "poisson_ratio": 0.3, "density": 1000, "damping": 0.01}}]})");
  // Squash flat: every vertex's height scaled by 1/20.
  for (auto& x : s.state.position) x.y() *= 0.05;
  test::run_steps(s, 400);
  Real volume = 0;
  for (const auto& t : s.model.objects[0].tets) {
    const auto& x = s.state.position;
    volume += tet_signed_volume(x[t[0]], x[t[1]], x[t[2]], x[t[3]]);
  }
  const Real rest = 0.2 * 0.2 * 0.2;
  fmt::print("squashed block: volume {:.6e} m^3 vs rest {:.6e} m^3\n", volume, rest);
  EXPECT_NEAR(volume, rest, 0.01 * rest);
}

TEST(SoftBodyValidation, CantileverDeflectionConvergesWithSubsteps) {
  // A 1 m x 0.1 m x 0.1 m cantilever clamped at x = 0 sags under gravity. The tip deflection as
  // the substep count doubles must form a converging sequence: successive differences shrink.
  auto tip = [](int substeps) {
    Scene s = test::scene_from_json(fmt::format(R"({{"name": "cantilever", "settings": {{"dt": 0.01, "substeps": {},
        "gravity": [0, -9.81, 0]}},
      "objects": [{{"name": "beam", "kind": "soft_body",
        "mesh": {{"type": "box", "min": [0, 0, 0], "max": [1, 0.1, 0.1], "cells": [10, 2, 2]}},
        "material": {{"youngs_modulus": 1e7, "poisson_ratio": 0.3, "density": 1000}},
        "pin": [{{"box": {{"min": [-1, -1, -1], "max": [0.001, 1, 1]}}}}]}}]}})",
                                                substeps));
    // Undamped, released from rest: the time average of the tip over 4 s (about 6 periods of the
    // first bending mode) estimates the static deflection.
    Real y = 0;
    long n = 0;
    StageTimer timer;
    for (int step = 0; step < 400; ++step) {
      s.formulation->step(s.model, s.state, timer, solver_thread_count(s.model));
      for (Index p = 0; p < s.model.particle_count(); ++p)
        if (s.model.particle_rest_position[p].x() > 0.999)
          y += s.state.position[p].y() - s.model.particle_rest_position[p].y(), ++n;
    }
    return -y / n;
  };
  const Real d20 = tip(20), d40 = tip(40), d80 = tip(80), d160 = tip(160);
  fmt::print("cantilever tip deflection (m): 20 substeps {:.5f}, 40 {:.5f}, 80 {:.5f}, 160 {:.5f}\n", d20, d40, d80, d160);
  EXPECT_GT(d160, 0);
  EXPECT_LT(std::abs(d160 - d80), std::abs(d80 - d40));
  EXPECT_LT(std::abs(d80 - d40), std::abs(d40 - d20));
  EXPECT_LT(std::abs(d160 - d80), 0.05 * d160);  // within 5 % of its neighbour at the finest level
}
