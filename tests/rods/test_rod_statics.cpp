// Cosserat rods at rest against beam theory, under both formulations: a cantilever under its weight
// and a tip load (Euler-Bernoulli), a rod twisted by an end torque (Saint-Venant torsion), a stiff
// steel rod stretched by a hanging weight (Hooke), and a cantilever bent far by its weight against
// the elastica (a shooting solution of its equilibrium, below).
//
// Static answers: under "xpbd" the rod is damped (Kelvin-Voigt, `damping_time`) and run until it
// settles; under "nmd" every step is 1 s, far longer than the rod's periods, so each step is a
// linearised solve of the static balance relaxed by SPOOK (as in the Servin beam test).
//
// Discretisation: the segments are rigid and their strains live at the junctions, each standing
// for the length between two segment centres; a clamp stands for the half segment at its end. An
// end load acts at the free end of the last segment, whose outer half has no compliance: stretch
// and twist under an end load come out (L - l/2) / L of the continuum's (0.5 % at 100 segments),
// bending under a tip load to O((l/L)^2) because the moment vanishes at the tip.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <cmath>
#include <string>

#include "moreau/math/types.hpp"
#include "moreau/world.hpp"

namespace moreau {
namespace {

constexpr Real kG = 9.81;

struct Run {
  std::string solver;  // "xpbd" or "nmd"
  int steps = 0;
};
// Static runs: xpbd with 20 substeps of a 0.01 s step for 3 s; nmd direct with 25 steps of 1 s.
const Run kXpbd{"xpbd", 300};
const Run kNmd{"nmd", 25};

std::string settings(const Run& run, const char* gravity, int xpbd_iterations = 1, int xpbd_substeps = 20) {
  if (run.solver == "xpbd")
    return fmt::format(R"("settings": {{"dt": 0.01, "substeps": {}, "iterations": {}, "duration": 3, "gravity": {}}})",
                       xpbd_substeps, xpbd_iterations, gravity);
  const Real dt = run.solver == "nmd" ? 1 : 0.01;  // "nmd_dynamic": steps of 0.01 s
  return fmt::format(R"("settings": {{"solver": "nmd", "dt": {}, "duration": 25, "gravity": {}, "nmd": {{"method": "direct"}}}})",
                     dt, gravity);
}

// The probes' values after the run's steps.
std::vector<double> run_scene(const std::string& json, const Run& run) {
  World w = World::from_json(json);
  for (int s = 0; s < run.steps; ++s) w.step();
  return w.probe_values();
}

// A 1 m rod along x at height 1 m, radius 1 cm, clamped at x = 0; `extra` adds objects and joints.
std::string cantilever(const Run& run, int segments, Real youngs, Real density, const std::string& extra_objects,
                       const std::string& joints) {
  return fmt::format(
      R"({{"name": "cantilever", {},
      "objects": [{{"name": "rod", "kind": "rod", "points": [[0, 1, 0], [1, 1, 0]], "segments": {}, "radius": 0.01,
                    "youngs_modulus": {}, "poisson_ratio": 0.3, "density": {}, "start": "clamped", "damping_time": 0.02}}{}],
      "joints": [{}],
      "probes": [{{"name": "tip", "type": "point", "object": "rod", "vertex": {}, "quantity": "displacement"}}]}})",
      settings(run, "[0, -9.81, 0]"), segments, youngs, density, extra_objects, joints, segments);
}

constexpr Real kRadius = 0.01, kLength = 1;
const Real kArea = kPi * kRadius * kRadius, kInertia = kPi * std::pow(kRadius, 4) / 4;

// A light rod (E = 10 GPa, 100 kg/m^3) under its weight q, then with a 50 g sphere hung at its tip
// (F = 0.49 N): the tip sags q L^4 / (8 E I) = 0.49 mm and F L^3 / (3 E I) = 2.08 mm more, 0.26 % of
// the length in all, where beam theory is linear to about 1e-5. The tip load's share is the
// difference of the two runs.
void check_tip_load(const Run& run) {
  const Real E = 1e10, density = 100, mass = 0.05;
  const Real q = density * kArea * kG, F = mass * kG, EI = E * kInertia;
  const Real own = -run_scene(cantilever(run, 20, E, density, "", ""), run)[1];
  const std::string sphere = fmt::format(
      R"(, {{"name": "weight", "kind": "rigid_body", "shape": {{"type": "sphere", "radius": 0.004}}, "position": [1, 1, 0], "mass": {}}})",
      mass);
  const std::string hang = R"({"name": "hang", "type": "spherical", "bodies": [{"object": "rod", "vertex": 20}, "weight"]})";
  const Real loaded = -run_scene(cantilever(run, 20, E, density, sphere, hang), run)[1];
  const Real weight_theory = q * std::pow(kLength, 4) / (8 * EI), tip_theory = F * std::pow(kLength, 3) / (3 * EI);
  std::printf("rod cantilever, %s, 20 segments: own weight %.6e m (q L^4/8EI %.6e, %+.2f %%), tip load %.6e m "
              "(F L^3/3EI %.6e, %+.2f %%)\n",
              run.solver.c_str(), own, weight_theory, 100 * (own / weight_theory - 1), loaded - own, tip_theory,
              100 * ((loaded - own) / tip_theory - 1));
  EXPECT_NEAR(own / weight_theory, 1, 0.02);
  EXPECT_NEAR((loaded - own) / tip_theory, 1, 0.02);
}

// `bending_modulus` sets the E of bending alone: the same light rod with E = 1 TPa for stretch and
// shear but bending at 10 GPa sags as the 10 GPa rod does, q L^4 / (8 E_b I), within the same 2 %
// (without the key it would sag 100 times less).
TEST(RodStatics, BendingModulusSetsTheBendingStiffnessAlone) {
  const Real E_b = 1e10, density = 100;
  World w = World::from_json(cantilever(kXpbd, 20, 1e12, density, "", ""), {"objects.rod.bending_modulus=1e10"});
  for (int s = 0; s < kXpbd.steps; ++s) w.step();
  const Real sag = -w.probe_values()[1], theory = density * kArea * kG * std::pow(kLength, 4) / (8 * E_b * kInertia);
  std::printf("rod cantilever, E = 1 TPa, bending modulus 10 GPa: own weight %.6e m (q L^4/8 E_b I %.6e, %+.2f %%)\n", sag,
              theory, 100 * (sag / theory - 1));
  EXPECT_NEAR(sag / theory, 1, 0.02);
}

TEST(RodStatics, CantileverSagsAsEulerBernoulliUnderXpbd) { check_tip_load(kXpbd); }
TEST(RodStatics, CantileverSagsAsEulerBernoulliUnderNmd) { check_tip_load(kNmd); }

// A rod of 100 segments clamped at x = 0, twisted at x = 1 by a hinge about x whose velocity drive
// saturates at T = 0.5 N m (its target speed is never reached): weightless, G = E / 2.6, J = pi r^4/2,
// so the end turns T L / (G J) = 0.0828 rad, small enough for the linear theory. Under xpbd the
// drive (Gauss-Seidel, after the direct solve of the rod) and the rod meet only through the
// iterations of a substep: with one iteration the end turns 0.84 rad, with 5 0.18 rad, with 20
// the rod's own answer (the segments' twist inertia is small beside the junctions' stiffness per
// substep, so each pass undoes most of the other's), hence 20 iterations here.
void check_twist(const Run& run) {
  const Real E = 1e9, G = E / 2.6, J = kPi * std::pow(kRadius, 4) / 2, T = 0.5;
  const std::string json = fmt::format(
      R"({{"name": "twist", {},
      "objects": [{{"name": "rod", "kind": "rod", "points": [[0, 1, 0], [1, 1, 0]], "segments": 100, "radius": 0.01,
                    "youngs_modulus": {}, "poisson_ratio": 0.3, "density": 1000, "start": "clamped", "damping_time": 0.02}}],
      "joints": [{{"name": "wrench", "type": "hinge", "bodies": ["world", {{"object": "rod", "vertex": 100}}], "axis": [1, 0, 0],
                   "drive": {{"target_velocity": 100, "max_torque": {}}}}}],
      "probes": [{{"name": "twist", "type": "twist", "object": "rod"}}]}})",
      settings(run, "[0, 0, 0]", 20), E, T);
  // xpbd: 0.5 s (the twist settles to 1e-8 within 0.4 s); nmd: static steps.
  const Real twist = run_scene(json, run.solver == "xpbd" ? Run{"xpbd", 50} : run)[0], theory = T * kLength / (G * J);
  std::printf("rod twist, %s, 100 segments: %.6e rad, T L / (G J) %.6e rad (%+.3f %%; the model's (L - l/2) / L: -0.5 %%)\n",
              run.solver.c_str(), twist, theory, 100 * (twist / theory - 1));
  EXPECT_NEAR(twist / theory, 1, 0.01);
}

TEST(RodStatics, EndTorqueTwistsTheRodByTLOverGJUnderXpbd) { check_twist(kXpbd); }
TEST(RodStatics, EndTorqueTwistsTheRodByTLOverGJUnderNmd) { check_twist(kNmd); }

}  // namespace
}  // namespace moreau

namespace moreau {
namespace {

// A steel rod (E = 200 GPa, 7800 kg/m^3) of 100 segments hanging 1 m from a pin, a 100 kg sphere on
// its lower end: it stretches by (F L + q L^2 / 2) / (E A) = 15.8 um, F the sphere's weight and q
// the rod's per metre. The direct tree solver holds the junctions exactly each substep, so one
// iteration and five give the same stretch (xpbd); nmd solves the same rows directly, in steps of
// 0.01 s: the rod swings on its pin as a pendulum (3.1 rad/s), which steps of 1 s would not follow.
const Run kNmdDynamic{"nmd_dynamic", 100};

Real hanging_stretch(const Run& run, int xpbd_iterations) {
  const std::string json = fmt::format(
      R"({{"name": "hanging", {},
      "objects": [{{"name": "rod", "kind": "rod", "points": [[0, 2, 0], [0, 1, 0]], "segments": 100, "radius": 0.01,
                    "youngs_modulus": 2e11, "poisson_ratio": 0.3, "density": 7800, "start": "pinned", "damping_time": 0.002}},
                  {{"name": "weight", "kind": "rigid_body", "shape": {{"type": "sphere", "radius": 0.05}}, "position": [0, 0.95, 0], "mass": 100}}],
      "joints": [{{"name": "hook", "type": "spherical", "bodies": [{{"object": "rod", "vertex": 100}}, "weight"]}}],
      "probes": [{{"name": "end", "type": "point", "object": "rod", "vertex": 100, "quantity": "displacement"}}]}})",
      settings(run, "[0, -9.81, 0]", xpbd_iterations));
  return -run_scene(json, run)[1];
}

TEST(RodStatics, StiffSteelRodStretchesByFLOverEAWhateverTheIterations) {
  const Real area = kPi * 1e-4, EA = 2e11 * area, F = 100 * kG, q = 7800 * area * kG;
  const Real theory = (F + q / 2) / EA;  // L = 1 m
  const Real one = hanging_stretch(kXpbd, 1), five = hanging_stretch(kXpbd, 5), nmd = hanging_stretch(kNmdDynamic, 1);
  std::printf("steel rod, 100 segments, 100 kg: stretch %.6e m (1 iteration), %.6e m (5), %.6e m (nmd); (F L + q L^2/2) / "
              "(E A) %.6e m (%+.3f %%)\n",
              one, five, nmd, theory, 100 * (one / theory - 1));
  EXPECT_NEAR(one / theory, 1, 0.01);
  EXPECT_NEAR(nmd / theory, 1, 0.01);
  EXPECT_NEAR(five / one, 1, 1e-6);  // the direct solve's answer does not depend on the iterations
}

// The elastica of a cantilever bent far by its own weight q: with arc length s, the angle theta
// and the bending moment m = E I theta',
//   theta' = m / (E I),  m' = q (L - s) cos theta,  x' = cos theta,  y' = sin theta,
// (the weight of the rod beyond s turns the section at s), clamped at s = 0 (theta = 0) and free
// at s = L (m = 0). Shooting on m(0) by bisection, RK4 on 4000 steps: the tip's (x, y).
Vec2 elastica_tip(Real q, Real EI, Real L) {
  auto tip = [&](Real m0, Vec2* end) {
    Eigen::Vector4d y(0, m0, 0, 0);  // theta, m, x, y
    auto f = [&](Real s, const Eigen::Vector4d& u) {
      return Eigen::Vector4d(u[1] / EI, q * (L - s) * std::cos(u[0]), std::cos(u[0]), std::sin(u[0]));
    };
    const int n = 4000;
    const Real h = L / n;
    for (int k = 0; k < n; ++k) {
      const Real s = k * h;
      const Eigen::Vector4d k1 = f(s, y), k2 = f(s + h / 2, y + h / 2 * k1), k3 = f(s + h / 2, y + h / 2 * k2),
                            k4 = f(s + h, y + h * k3);
      y += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
    }
    if (end) *end = Vec2(y[2], y[3]);
    return y[1];  // m(L): 0 at the answer
  };
  Real lo = -q * L * L / 2, hi = 0;  // m(L) <= 0 at lo, > 0 at hi
  for (int k = 0; k < 80; ++k) {
    const Real mid = (lo + hi) / 2;
    (tip(mid, nullptr) > 0 ? hi : lo) = mid;
  }
  Vec2 end;
  tip((lo + hi) / 2, &end);
  return end;
}

// q L^3 / (E I) = 5: small-deflection theory would drop the tip 0.625 L; the elastica's tip ends
// at x = 0.85 L, 0.50 L down. The rod (50 segments) must land within 1 % of L of it. Its first
// mode (4.9 rad/s) is critically damped by damping_time = 0.4 s, so xpbd settles within its 3 s.
void check_elastica(const Run& run) {
  const Real density = 1000, q = density * kArea * kG, EI = q / 5, E = EI / kInertia;
  const Vec2 theory = elastica_tip(q, EI, kLength);
  const std::string json = fmt::format(
      R"({{"name": "elastica", {},
      "objects": [{{"name": "rod", "kind": "rod", "points": [[0, 1, 0], [1, 1, 0]], "segments": 50, "radius": 0.01,
                    "youngs_modulus": {}, "poisson_ratio": 0.3, "density": {}, "start": "clamped", "damping_time": 0.4}}],
      "probes": [{{"name": "tip", "type": "point", "object": "rod", "vertex": 50}}]}})",
      settings(run, "[0, -9.81, 0]"), E, density);
  const std::vector<double> tip = run_scene(json, run);
  const Vec2 rod(tip[0], tip[1] - 1);
  std::printf("elastica q L^3 / E I = 5, %s, 50 segments: tip (%.5f, %.5f) m, shooting (%.5f, %.5f) m, off by %.2e m\n",
              run.solver.c_str(), rod.x(), rod.y(), theory.x(), theory.y(), (rod - theory).norm());
  EXPECT_LT((rod - theory).norm(), 0.01 * kLength);
}

TEST(RodStatics, CantileverBentFarByItsWeightFollowsTheElasticaUnderXpbd) { check_elastica(kXpbd); }
TEST(RodStatics, CantileverBentFarByItsWeightFollowsTheElasticaUnderNmd) { check_elastica(kNmd); }

}  // namespace
}  // namespace moreau
