// The XPBD formulation on problems with closed-form answers.
#include <gtest/gtest.h>

#include <cmath>

#include "moreau/model/diagnostics.hpp"
#include "test_helpers.hpp"

using namespace moreau;

TEST(XpbdBasics, FreeFallFollowsSymplecticEulerExactly) {
  // One soft body with no colliders; every particle falls. With substep h the scheme is
  // symplectic Euler, whose exact solution after n substeps is
  //   y_n = y0 + v0 t + g h^2 n (n+1)/2 = y0 + v0 t + g t^2/2 + g h t/2,
  // i.e. the analytic parabola plus the known first-order bias g h t/2. We check both to round-off.
  Scene s = test::scene_from_json(R"({"name": "fall", "settings": {"dt": 0.01, "substeps": 10, "gravity": [0, -9.81, 0]},
    "objects": [{"name": "b", "kind": "soft_body", "velocity": [1, 2, 0],
      "mesh": {"type": "box", "min": [0, 0, 0], "max": [0.1, 0.1, 0.1], "cells": [1, 1, 1]},
      "material": {"youngs_modulus": 1e5, "poisson_ratio": 0.3, "density": 1000}}]})");
  test::run_steps(s, 100);
  const Real t = 1.0, h = 0.001, g = -9.81;
  for (Index p = 0; p < s.model.particle_count(); ++p) {
    const Vec3 x0 = s.model.particle_rest_position[p];
    EXPECT_NEAR(s.state.position[p].x(), x0.x() + 1.0 * t, 1e-12);
    EXPECT_NEAR(s.state.position[p].y(), x0.y() + 2.0 * t + 0.5 * g * t * t + 0.5 * g * h * t, 1e-11);
    EXPECT_NEAR(s.state.velocity[p].y(), 2.0 + g * t, 1e-11);
  }
}

TEST(XpbdBasics, SpringPeriodIsIndependentOfIterations) {
  // methods.md sec. 1 test: a particle on a compliant distance constraint (rest length 1, m = 1,
  // alpha = 1e-3 m/N) starting at x = 1.5 oscillates with period 2 pi sqrt(m alpha) = 0.1987 s for
  // any iteration count. The model is built directly: a pinned particle and a free one.
  const Real alpha = 1e-3, expected_period = 2 * kPi * std::sqrt(1.0 * alpha);
  for (int iterations : {1, 4, 16}) {
    Model m;
    m.settings.gravity = Vec3::Zero();
    m.settings.dt = 1e-3;
    m.settings.substeps = 10;
    m.settings.iterations = iterations;
    m.settings.threads = 1;
    ObjectInfo spring;
    spring.name = "spring";
    spring.particle_end = 2;
    m.objects.push_back(spring);
    m.particle_rest_position = {Vec3(0, 0, 0), Vec3(1.5, 0, 0)};
    m.particle_mass = {1, 1};
    m.particle_inv_mass = {0, 1};
    m.particle_inv_inertia = {0, 0};
    m.particle_radius = {0.1, 0.1};
    m.particle_collider_gap = {0, 0};
    m.particle_object = {0, 0};
    m.family<DistanceConstraints>().add(0, 1, 1.0, alpha, 0, 0);
    m.color_constraints();
    State st = make_rest_state(m);
    StageTimer timer;
    XpbdWorkspace workspace;
    // Times of successive maxima of x(t) give the period.
    std::vector<Real> peaks;
    Real prev2 = 1.5, prev1 = 1.5;
    for (int step = 0; step < 1000; ++step) {
      xpbd_step(m, st, workspace, timer, 1);
      const Real x = st.position[1].x();
      if (prev1 > prev2 && prev1 >= x && step > 1) peaks.push_back(st.time - m.settings.dt);
      prev2 = prev1;
      prev1 = x;
    }
    ASSERT_GE(peaks.size(), 3u);
    const Real period = (peaks.back() - peaks.front()) / (peaks.size() - 1);
    // Tolerance 2 %: peaks are located to one step (1 ms = 0.5 % of a period, averaged over
    // several periods) and implicit Euler's frequency error at h = 1e-4 s is (omega h)^2/2 ~ 5e-5.
    EXPECT_NEAR(period, expected_period, 0.02 * expected_period) << "iterations " << iterations;
  }
}

TEST(XpbdBasics, UnloadedNeoHookeanBlockStaysExactlyStill) {
  // Rest stability of stable Neo-Hookean: at F = I the forces of C_H and C_D cancel exactly.
  Scene s = test::scene_from_json(R"({"name": "rest", "settings": {"dt": 0.01, "substeps": 10, "gravity": [0, 0, 0]},
    "objects": [{"name": "b", "kind": "soft_body",
      "mesh": {"type": "box", "min": [0, 0, 0], "max": [1, 0.5, 0.5], "cells": [6, 3, 3]},
      "material": {"youngs_modulus": 1e6, "poisson_ratio": 0.45, "density": 1000}}]})");
  test::run_steps(s, 100);
  Real max_displacement = 0;
  for (Index p = 0; p < s.model.particle_count(); ++p)
    max_displacement = std::max(max_displacement, (s.state.position[p] - s.model.particle_rest_position[p]).norm());
  // Round-off only: each projection at rest computes dlambda from C_H = 1 - gamma and C_D = sqrt(3)
  // whose forces cancel to ~1e-16 relative; 1e-12 m over 1000 substeps is that accumulated.
  EXPECT_LT(max_displacement, 1e-12);
}

TEST(XpbdBasics, MomentumOfSpinningSoftBodyIsConserved) {
  // No gravity, no colliders: every constraint is translation and rotation invariant, so each
  // projection conserves linear momentum exactly and angular momentum at the positions where its
  // gradient is evaluated.
  Scene s = test::scene_from_json(R"({"name": "spin", "settings": {"dt": 0.01, "substeps": 20, "gravity": [0, 0, 0]},
    "objects": [{"name": "b", "kind": "soft_body", "velocity": [0.3, 0, -0.2], "angular_velocity": [0.5, 3, 1],
      "mesh": {"type": "box", "min": [0, 0, 0], "max": [0.4, 0.2, 0.2], "cells": [4, 2, 2]},
      "material": {"youngs_modulus": 1e5, "poisson_ratio": 0.3, "density": 1000}}]})");
  const Vec3 p0 = linear_momentum(s.model, s.state, -1);
  const Vec3 L0 = angular_momentum(s.model, s.state, -1, Vec3::Zero());
  test::run_steps(s, 100);
  const Vec3 p1 = linear_momentum(s.model, s.state, -1);
  const Vec3 L1 = angular_momentum(s.model, s.state, -1, Vec3::Zero());
  // Linear momentum: round-off of 2000 substeps of sums of O(1) terms.
  EXPECT_LT((p1 - p0).norm(), 1e-12 * std::max(1.0, p0.norm()) * 100);
  // Angular momentum: XPBD evaluates each gradient at the current iterate, not at the substep
  // start, which costs O((omega h)^2) per substep relative drift (the same effect that makes a
  // PBD pendulum lose speed). With omega h = 3 * 5e-4 this is ~1e-6 per substep, ~2e-3 over 2000;
  // we bound the measured drift by 1 %.
  EXPECT_LT((L1 - L0).norm(), 0.01 * L0.norm());
  fmt::print("angular momentum relative drift over 1 s: {:.3e}\n", (L1 - L0).norm() / L0.norm());
}
