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
// A small Kelvin-Voigt damping (2 ms) takes the higher modes away within 0.5 s (the second decays
// at 12/s, the first at 0.15/s, which moves its frequency by 2e-4); the period is the mean spacing
// of the tip's upward zero crossings from 0.5 s to 4 s.
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
