// Sub-particle drift of immiscible liquids (settings.fluid.phase_drift, phase_drift.hpp): single
// particles of oil dispersed in water rise at the terminal speed of a drop of one particle's
// volume, by trading places with the water above them, under xpbd and nmd; a trade keeps
// momentum, each liquid's mass and the set of occupied positions; oil resting on water stays on
// it, and the drift carries back up what creeps down the walls; runs repeat bit for bit on one
// and two threads.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "moreau/fluids/fluid_scratch.hpp"
#include "moreau/fluids/phase_drift.hpp"
#include "moreau/model/model.hpp"
#include "test_helpers.hpp"

namespace moreau {
namespace {

constexpr Real kGravity = 9.81;

// The Schiller-Naumann balance in its two limits: Stokes' law for a small, slow sphere (Re << 1,
// where C_d = 24/Re (1 + 0.15 Re^0.687) is 24/Re to within 0.15 Re^0.687) and Newton's regime
// (C_d = 0.44) for an inviscid liquid.
TEST(FluidPhaseDrift, TerminalSpeedMeetsStokesAndNewtonLimits) {
  const Real d = 1e-5, mu = 1e-3, drop = 900, liquid = 1000;
  const Real stokes = (liquid - drop) * kGravity * d * d / (18 * mu);
  const Real u = terminal_drift_speed(d, drop, liquid, mu, kGravity);
  const Real re = liquid * u * d / mu;
  EXPECT_LT(re, 1e-3);
  EXPECT_NEAR(u, stokes / (1 + 0.15 * std::pow(re, 0.687)), 1e-9 * stokes);
  EXPECT_NEAR(u, stokes, 2e-3 * stokes);  // 0.15 Re^0.687 < 1.3e-3

  // At Re = 141 (the dispersed oil below), the speed returned balances weight and drag.
  const Real d_oil = 2.423244e-3, u_oil = terminal_drift_speed(d_oil, drop, liquid, mu, kGravity);
  const Real re_oil = liquid * u_oil * d_oil / mu;
  const Real drag = 24 / re_oil * (1 + 0.15 * std::pow(re_oil, 0.687)) * liquid * u_oil * u_oil * kPi * d_oil * d_oil / 8;
  const Real weight = (liquid - drop) * kGravity * kPi * d_oil * d_oil * d_oil / 6;
  EXPECT_NEAR(re_oil, 141.1, 0.1);
  EXPECT_NEAR(drag, weight, 1e-9 * weight);

  const Real big = 0.01;  // 1 cm, inviscid: drag 0.44 rho u^2 pi d^2 / 8 = (rho_l - rho_d) g pi d^3 / 6
  const Real newton = std::sqrt(4 * (liquid - drop) * kGravity * big / (3 * 0.44 * liquid));
  EXPECT_NEAR(terminal_drift_speed(big, drop, liquid, 0, kGravity), newton, 1e-9 * newton);
  EXPECT_EQ(terminal_drift_speed(big, liquid, liquid, mu, kGravity), 0);
}

// A 23 x 39 x 23 mm tank of water (r = 0.98 mm, 12 x 20 x 12 sites) with 32 single oil particles
// on every third site of two low layers (three spacings apart, beyond each other's kernel support
// of two).
// Each lattice row is written as runs of one liquid.
std::string dispersed_oil_scene(bool drift, const char* solver = "xpbd") {
  constexpr int nx = 12, ny = 20;
  auto oil_site = [](int i, int j, int k) { return (j == 1 || j == 4) && i % 3 == 1 && k % 3 == 1; };
  // r = 2^-10 m (spacing 2^-9): the block corners are exact binary fractions, so each block is
  // exactly whole spacings wide.
  constexpr Real spacing = 1.0 / 512;
  auto lo = [&](int i) { return (i - nx / 2) * spacing; };
  std::string oil, water;
  for (int k = 0; k < nx; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx;) {
        const bool is_oil = oil_site(i, j, k);
        int end = i + 1;
        while (end < nx && oil_site(end, j, k) == is_oil) ++end;
        std::string& out = is_oil ? oil : water;
        out += fmt::format(R"({}{{"min": [{}, {}, {}], "max": [{}, {}, {}]}})", out.empty() ? "" : ", ", lo(i),
                           spacing * j, lo(k), lo(end), spacing * (j + 1), lo(k + 1));
        i = end;
      }
  return fmt::format(R"({{"name": "drift", "settings": {{"solver": "{}", "dt": 0.004, "substeps": 2, "iterations": 4,
      "fluid": {{"phase_drift": {}}}}},
    "objects": [
      {{"name": "tank", "kind": "collider", "inside": true,
        "shape": {{"type": "box", "center": [0, 0.025, 0], "half_extents": [{}, 0.025, {}]}}}},
      {{"name": "water", "kind": "fluid", "particle_radius": {}, "viscosity": 0.001, "blocks": [{}]}},
      {{"name": "oil", "kind": "fluid", "particle_radius": {}, "density": {}, "viscosity": 0.001, "blocks": [{}]}}]}})",
                     solver, drift ? "true" : "false", lo(nx), lo(nx), spacing / 2, water, spacing / 2, 900, oil);
}

constexpr Index kOilPhase = 1;  // fluids get their phases in scene order

Real mean_oil_height(const Scene& scene) {
  const FluidState& f = scene.state.fluid;
  Real sum = 0;
  Index n = 0;
  for (Index i = 0; i < f.count; ++i)
    if (f.phase[i] == kOilPhase) sum += f.position[i].y(), ++n;
  return sum / static_cast<Real>(n);
}

// The mean climb of the 32 oil particles over 0.3 s, less that of a twin without the drift (which
// shows what the liquid's own motion does: it settles from the lattice, and a particle does not
// rise by itself, docs/scene-format.md), as a speed.
Real drift_speed_measured(const char* solver, Real& u) {
  Scene drifting = test::scene_from_json(dispersed_oil_scene(true, solver));
  Scene jammed = test::scene_from_json(dispersed_oil_scene(false, solver));
  EXPECT_EQ(drifting.state.fluid.count, 12 * 20 * 12);
  u = drifting.model.fluid.drift_speed[kOilPhase * 2 + 0];  // oil dispersed in water
  const Real start = mean_oil_height(drifting);
  EXPECT_EQ(start, mean_oil_height(jammed));
  const long steps = 75;
  const Real T = steps * drifting.model.settings.dt;
  test::run_steps(drifting, steps);
  test::run_steps(jammed, steps);
  const Real rise = mean_oil_height(drifting) - start, own = mean_oil_height(jammed) - start;
  std::printf("%s: oil rise over %.2f s: %.2f mm with drift, %.2f mm without; drift speed %.4f m/s against u = %.4f m/s\n",
              solver, T, 1e3 * rise, 1e3 * own, (rise - own) / T, u);
  EXPECT_LT(std::abs(own), 1e-3);
  return (rise - own) / T;
}

// Over 0.3 s the drift alone lifts each particle by u T = 17 mm, in some eight trades. Tolerance
// 15 %: 2.5 standard errors of a count of about 270 trades (1/sqrt(270) = 6 %), each a chance
// event, over the 32 particles.
TEST(FluidPhaseDrift, DispersedOilRisesAtTheTerminalSpeedOfOneParticle) {
  Real u = 0;
  const Real measured = drift_speed_measured("xpbd", u);
  // d = (6 (2 r)^3 / pi)^(1/3) = 2.42 mm: Re = 141, u = 0.058230 m/s (the balance is checked above).
  EXPECT_NEAR(u, 0.058230, 1e-6);
  EXPECT_NEAR(measured, u, 0.15 * u);  // measured: +2.7 %
}

// Under nmd the same particles climb 17 % slower than u (0.0485 m/s), for a cause not found: the
// trades are the same pass, so the difference is in how the velocity-level solve moves a particle
// after its trade. The bounds guard that figure (about 2 standard errors below it, and the xpbd
// bound above) until the cause is understood.
TEST(FluidPhaseDrift, DispersedOilRisesUnderNmd) {
  Real u = 0;
  const Real measured = drift_speed_measured("nmd", u);
  EXPECT_GT(measured, 0.7 * u);
  EXPECT_LT(measured, 1.15 * u);
}

TEST(FluidPhaseDrift, ATradeKeepsMomentumMassAndTheOccupiedPositions) {
  Scene scene = test::scene_from_json(dispersed_oil_scene(true));
  test::run_steps(scene, 10);
  FluidState& f = scene.state.fluid;
  FluidScratch scratch;
  auto momentum = [&] {
    Vec3 p = Vec3::Zero();
    for (Index i = 0; i < f.count; ++i) p += f.mass[i] * f.velocity[i];
    return p;
  };
  auto sorted_positions = [&] {
    std::vector<std::array<Real, 3>> x;
    for (Index i = 0; i < f.count; ++i) x.push_back({f.position[i].x(), f.position[i].y(), f.position[i].z()});
    std::sort(x.begin(), x.end());
    return x;
  };
  auto potential = [&] {
    Real e = 0;
    for (Index i = 0; i < f.count; ++i) e += f.mass[i] * kGravity * f.position[i].y();
    return e;
  };
  const Vec3 p0 = momentum();
  const auto x0 = sorted_positions();
  const Real e0 = potential();
  const std::vector<Index> phase0 = f.phase;
  // A late time draws other trades than the run's; repeat until some happen.
  Index trades = 0;
  for (long k = 0; k < 50 && trades == 0; ++k) trades = drift_phases(scene.model, f, scratch, 100000 + k, 1);
  ASSERT_GT(trades, 0);
  EXPECT_TRUE(f.lists_stale);
  EXPECT_EQ(momentum(), p0);        // each particle keeps its mass and velocity, summed in the same order
  EXPECT_EQ(sorted_positions(), x0);  // the same positions, occupied by other particles
  EXPECT_EQ(f.phase, phase0);
  EXPECT_LT(potential(), e0);       // the lighter went up
}

// Oil resting on water (r = 1 mm, 1 cm on 2 cm in a 24 mm square tank, both with surface tension):
// the layers stay sharp. Without the drift the oil creeps down the side walls between the water and
// the wall (walls attract neither liquid, and the oil's lower tension lets it wet them better,
// docs/scene-format.md): 62 particles more than a spacing below the interface after 0.4 s. With it,
// the creeping particles trade back up as they go down (measured: 8). Trades happen only where an
// oil particle lies r/2 or more below a water particle, and each moves the oil up; the bound, a
// third of the count without the drift, leaves room for the creep to differ in detail.
TEST(FluidPhaseDrift, AStableLayeringStaysSharp) {
  const std::string layers = R"({"name": "layers", "settings": {"dt": 0.004, "substeps": 2, "iterations": 4,
      "fluid": {"phase_drift": DRIFT}},
    "objects": [
      {"name": "tank", "kind": "collider", "inside": true,
        "shape": {"type": "box", "center": [0, 0.025, 0], "half_extents": [0.012, 0.025, 0.012]}},
      {"name": "water", "kind": "fluid", "particle_radius": 0.001, "surface_tension": 0.072,
       "block": {"min": [-0.012, 0, -0.012], "max": [0.012, 0.02, 0.012]}},
      {"name": "oil", "kind": "fluid", "particle_radius": 0.001, "density": 900, "surface_tension": 0.032,
       "block": {"min": [-0.012, 0.02, -0.012], "max": [0.012, 0.03, 0.012]}}]})";
  auto with = [&](const char* drift) {
    std::string s = layers;
    s.replace(s.find("DRIFT"), 5, drift);
    return test::scene_from_json(s);
  };
  // Particles more than one spacing on the wrong side of the interface (y = 2 cm at the start;
  // the layers settle by a fraction of a spacing).
  auto misplaced = [](const Scene& scene) {
    const FluidState& f = scene.state.fluid;
    Index n = 0;
    for (Index i = 0; i < f.count; ++i)
      n += f.phase[i] == kOilPhase ? f.position[i].y() < 0.018 : f.position[i].y() > 0.022;
    return n;
  };
  Scene drifting = with("true"), plain = with("false");
  test::run_steps(drifting, 100);
  test::run_steps(plain, 100);
  std::printf("misplaced after 0.4 s: %ld with drift, %ld without\n", static_cast<long>(misplaced(drifting)),
              static_cast<long>(misplaced(plain)));
  EXPECT_GT(misplaced(plain), 30);
  EXPECT_LE(3 * misplaced(drifting), misplaced(plain));
}

TEST(FluidPhaseDrift, RunsRepeatBitForBitOnOneAndTwoThreads) {
  const std::string json = dispersed_oil_scene(true);
  Scene one = test::scene_from_json(json, {"settings.threads=1"});
  Scene two = test::scene_from_json(json, {"settings.threads=2"});
  test::run_steps(one, 40);
  test::run_steps(two, 40);
  EXPECT_EQ(one.state.fluid.position, two.state.fluid.position);
  EXPECT_EQ(one.state.fluid.phase, two.state.fluid.phase);
}

}  // namespace
}  // namespace moreau
