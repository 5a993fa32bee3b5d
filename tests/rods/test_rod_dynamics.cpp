// Cosserat rods in motion: the first bending frequency of a cantilever against Euler-Bernoulli's
// beta_1 = 1.8751, under both formulations.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <cmath>
#include <vector>

#include "moreau/math/types.hpp"
#include "moreau/world.hpp"

namespace moreau {
namespace {

// A 1 m cantilever (E = 1 GPa, 1000 kg/m^3, r = 1 cm, 20 segments), weightless, set
// moving by a uniform 5 cm/s: its tip swings at omega_1 = beta_1^2 sqrt(E I / (rho A L^4)) =
// 17.58 rad/s (2.798 Hz). The segments' rotary inertia lowers it by about (beta_1 r / 2L)^2, 1e-4.
// A small Kelvin-Voigt damping (2 ms) takes the higher modes away within 0.5 s (a mode decays at
// omega^2 tau / 2: the second at 12/s, the first at 0.31/s, which moves its frequency by 2e-4);
// the period is the mean spacing of the tip's upward zero crossings from 0.5 s to 4 s.
Real first_frequency(const std::string& solver_settings, int steps_per_second) {
  World w = World::from_json(fmt::format(
      R"({{"name": "ringing", "settings": {{{}, "duration": 4, "gravity": [0, 0, 0]}},
      "objects": [{{"name": "rod", "kind": "rod", "points": [[0, 1, 0], [1, 1, 0]], "segments": 20, "radius": 0.01,
                    "youngs_modulus": 1e9, "poisson_ratio": 0.3, "density": 1000, "start": "clamped",
                    "damping_time": 0.002, "velocity": [0, 0.05, 0]}}],
      "probes": [{{"name": "tip", "type": "point", "object": "rod", "vertex": 20, "quantity": "displacement"}}]}})",
      solver_settings));
  std::vector<Real> crossings;
  Real before = 0;
  const int steps = 4 * steps_per_second;
  for (int s = 1; s <= steps; ++s) {
    w.step();
    const Real y = w.probe_values()[1], t = Real(s) / steps_per_second;
    if (t > 0.5 && before < 0 && y >= 0) crossings.push_back(t - y / (y - before) / steps_per_second);
    before = y;
  }
  EXPECT_GE(crossings.size(), 8u);
  return (crossings.size() - 1) / (crossings.back() - crossings.front());
}

TEST(RodDynamics, FirstBendingFrequencyMatchesEulerBernoulli) {
  const Real EI = 1e9 * kPi * 1e-8 / 4, rhoA = 1000 * kPi * 1e-4;
  const Real theory = 1.8751 * 1.8751 * std::sqrt(EI / rhoA) / (2 * kPi);
  const Real xpbd = first_frequency(R"("dt": 0.005, "substeps": 10)", 200);
  const Real nmd = first_frequency(R"("solver": "nmd", "dt": 0.001, "nmd": {"method": "direct"})", 1000);
  std::printf("rod cantilever, 20 segments: first frequency %.5f Hz (xpbd), %.5f Hz (nmd, 1 ms steps); Euler-Bernoulli "
              "%.5f Hz (%+.2f %%, %+.2f %%)\n",
              xpbd, nmd, theory, 100 * (xpbd / theory - 1), 100 * (nmd / theory - 1));
  EXPECT_NEAR(xpbd / theory, 1, 0.02);
  EXPECT_NEAR(nmd / theory, 1, 0.02);
}

}  // namespace
}  // namespace moreau

namespace moreau {
namespace {

// Greenhill's instability of a twisted rod with both ends clamped and no axial load: the lateral
// deflection w = y + i z of the straight rod obeys B w'''' - i M w''' = 0 (B = E I), and w = w' = 0
// at both ends leaves a solution only where tan(M L / 2B) = M L / 2B, first at M L / B = 8.987:
// the twist theta_c = M L / (G J) = 8.987 B / (G J) = 8.987 (1 + nu) for a round section. A 1 m rod
// (E = 1 GPa, nu = 0.3, 50 segments: theta_c = 11.68 rad) is clamped at x = 0; its far end is
// clamped in direction to a slider that runs freely along x (no axial load) and turned at 3 rad/s
// by a velocity-driven hinge (quasi-static: the rod's first bending mode is near 110 rad/s). Its
// weight sags it 1 mm, the imperfection that starts the buckling; past it, the rod throws a loop
// and the slider runs in. Reported: the twist when the middle has left the axis by 5 cm; below
// 0.9 theta_c the rod stays straight.
//
// Under nmd only: a rod held at both ends closes a loop through the world, and xpbd's direct
// solver takes trees only; the drive, solved after the rod by Gauss-Seidel, is undone by the
// rod's next direct solve each substep and the twist stalls at 2.7 rad.
struct Buckling {
  Real twist_at_buckling = -1, largest_offset_before = 0;
};
Buckling twist_until_buckled() {
  World w = World::from_json(R"({"name": "plectoneme",
      "settings": {"solver": "nmd", "dt": 0.002, "duration": 6, "nmd": {"method": "direct"}},
      "objects": [{"name": "rod", "kind": "rod", "points": [[0, 1, 0], [1, 1, 0]], "segments": 50, "radius": 0.01,
                   "youngs_modulus": 1e9, "poisson_ratio": 0.3, "density": 1000, "start": "clamped", "damping_time": 0.01},
                  {"name": "slider", "kind": "rigid_body", "shape": {"type": "box", "size": [0.02, 0.02, 0.02]},
                   "position": [1, 1, 0], "mass": 0.01}],
      "joints": [{"name": "rail", "type": "prismatic", "bodies": ["world", "slider"], "anchor": [1, 1, 0], "axis": [1, 0, 0]},
                 {"name": "twister", "type": "hinge", "bodies": ["slider", {"object": "rod", "vertex": 50}], "axis": [1, 0, 0],
                  "drive": {"target_velocity": 3}}],
      "probes": [{"name": "twist", "type": "twist", "object": "rod"},
                 {"name": "middle", "type": "point", "object": "rod", "vertex": 25, "quantity": "displacement"}]})");
  const Real theta_c = 8.987 * 1.3;
  Buckling b;
  for (int s = 0; s < 3000; ++s) {
    w.step();
    const std::vector<double> v = w.probe_values();
    const Real twist = v[0], offset = std::hypot(v[2], v[3]);
    if (twist < 0.9 * theta_c) b.largest_offset_before = std::max(b.largest_offset_before, offset);
    if (offset > 0.05) {
      b.twist_at_buckling = twist;
      break;
    }
  }
  return b;
}

TEST(RodDynamics, TwistedClampedRodBucklesAtGreenhillsTwist) {
  const Real theta_c = 8.987 * 1.3;
  const Buckling b = twist_until_buckled();
  std::printf("twisted clamped rod, nmd, 50 segments: buckled at a twist of %.3f rad, Greenhill %.3f rad (%+.1f %%); the "
              "middle kept within %.2e m of the axis below 0.9 of it\n",
              b.twist_at_buckling, theta_c, 100 * (b.twist_at_buckling / theta_c - 1), b.largest_offset_before);
  EXPECT_LT(b.largest_offset_before, 0.005);
  EXPECT_NEAR(b.twist_at_buckling / theta_c, 1, 0.1);
}

}  // namespace
}  // namespace moreau
