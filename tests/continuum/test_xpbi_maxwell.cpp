// XPBI's Maxwell fluid (plasticity "maxwell") as a whole body: watched for many relaxation
// times, a column under a plate creeps as a Newtonian liquid of viscosity mu lambda squeezed
// between frictionless plates; in an impact much shorter than its relaxation time it bounces like
// the elastic solid of the same modulus, and in one much longer it splashes like a liquid.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "moreau/scene/scene.hpp"

namespace moreau {
namespace {

void step(Scene& scene) {
  StageTimer timer;
  scene.formulation->step(scene.model, scene.state, timer, 1);
}

// Uniaxial creep between frictionless plates. A Newtonian liquid squeezed by a load N over its
// section A flows in pure extension at the axial rate d ln H / dt = -N / (3 eta A) (Trouton's
// extensional viscosity 3 eta), and its volume V = A H is kept. A Maxwell column's elastic strain
// (N / (E A), 0.6-0.7 % here) settles within a few relaxation times and then changes only as the
// section grows, so from 0.3 s (8 lambda) on it creeps as the liquid of viscosity mu lambda:
// its middle half shortens at the rate -N H / (3 eta V) and the whole column's 1 / H grows at
// N / (3 eta V).
TEST(XpbiMaxwell, AColumnUnderAPlateCreepsAsALiquidOfViscosityMuLambda) {
  const Real E = 1e5, nu = 0.3, lambda = 0.0375, density = 100, plate = 0.025, width = 0.02, tall = 0.08;
  const Real half_thickness = 0.01, r = 0.005, dt = 0.005;
  Scene scene = load_scene_text(fmt::format(R"({{"name": "creep", "settings": {{"solver": "xpbi", "dt": {}, "substeps": 10, "iterations": 20}},
      "objects": [{{"name": "ground", "kind": "collider", "shape": {{"type": "plane"}}, "friction": 0}},
                  {{"name": "column", "kind": "continuum", "blocks": [{{"min": [{}, 0, {}], "max": [{}, {}, {}]}}],
                    "spacing": {}, "density": {}, "youngs_modulus": {}, "poisson_ratio": {}, "friction": 0,
                    "plasticity": {{"model": "maxwell", "relaxation_time": {}}}}},
                  {{"name": "plate", "kind": "rigid_body", "shape": {{"type": "box", "half_extents": [0.03, {}, 0.03]}},
                    "position": [0, {}, 0], "mass": {}, "friction": 0}}],
      "joints": [{{"name": "guide", "type": "prismatic", "bodies": ["world", "plate"], "anchor": [0, {}, 0],
                   "axis": [0, 1, 0]}}]}})",
                                            dt, -width / 2, -width / 2, width / 2, tall, width / 2, r, density, E, nu,
                                            lambda, half_thickness, tall + half_thickness, plate, tall + half_thickness),
                                "creep");
  const ContinuumModel& c = scene.model.continuum;
  std::vector<Real> rest_y(c.size());
  for (Index i = 0; i < c.size(); ++i) rest_y[i] = scene.state.position[c.particle[i]].y();
  const Index plate_body = scene.model.objects[scene.model.find_object("plate")].body;
  auto height = [&] { return scene.state.rigid.position[plate_body].y() - half_thickness; };
  // The middle half: the layers 4 r above the bottom one and 4 r below the top one (16 in all).
  auto layer_mean = [&](Real rest_height) {
    Real sum = 0;
    int count = 0;
    for (Index i = 0; i < c.size(); ++i)
      if (std::abs(rest_y[i] - rest_height) < 1e-9) sum += scene.state.position[c.particle[i]].y(), ++count;
    return sum / count;
  };
  auto middle_length = [&] { return layer_mean(tall - 4.5 * r) - layer_mean(4.5 * r); };

  const Real eta = E / (2 * (1 + nu)) * lambda, volume = width * width * tall;
  // The load at mid-height, the plate and the upper half of the column: the strain rate is linear
  // in the load, which grows linearly down the column, so the mid-height load gives the mean rate.
  const Real load = 9.81 * (plate + density * volume / 2);
  const Real inverse_height_rate = load / (3 * eta * volume);  // d(1/H)/dt, 1/(m s)

  // Every 10 steps from 0.3 s to 0.7 s: time, 1/H, and the middle's measured against the
  // predicted strain rate by central differences.
  std::vector<Real> times, inverse_heights, lengths, heights;
  for (int k = 1; k <= 140; ++k) {
    step(scene);
    if (k >= 60 && k % 10 == 0)
      times.push_back(k * dt), inverse_heights.push_back(1 / height()), heights.push_back(height()),
          lengths.push_back(middle_length());
  }
  Real middle_ratio = 0;
  for (size_t i = 1; i + 1 < times.size(); ++i) {
    const Real measured = std::log(lengths[i + 1] / lengths[i - 1]) / (times[i + 1] - times[i - 1]);
    const Real predicted = -load * heights[i] / (3 * eta * volume);
    middle_ratio += measured / predicted / (times.size() - 2);
  }
  // Least-squares slope of 1/H against t.
  Real mt = 0, mh = 0;
  for (size_t i = 0; i < times.size(); ++i) mt += times[i] / times.size(), mh += inverse_heights[i] / times.size();
  Real stt = 0, sth = 0;
  for (size_t i = 0; i < times.size(); ++i) stt += (times[i] - mt) * (times[i] - mt), sth += (times[i] - mt) * (inverse_heights[i] - mh);
  const Real whole_ratio = sth / stt / inverse_height_rate;
  fmt::print("Maxwell creep (eta = {:.1f} Pa s): H {:.4f} m at 0.7 s; the middle half's strain rate {:+.2f} %, the whole "
             "column's d(1/H)/dt {:+.2f} % against the liquid's\n",
             eta, height(), 100 * (middle_ratio - 1), 100 * (whole_ratio - 1));
  // The middle half flows as the liquid within 5 % (+3.3 % measured; the same at 40 iterations).
  EXPECT_NEAR(middle_ratio, 1, 0.05);
  // The whole column creeps 8.2 % slower (the same at 40 iterations): as in the elastic cube
  // (test_xpbi_elastic.cpp), the layers at the plates, whose kernels are one-sided, strain less
  // than the middle. 12 % keeps that from growing unnoticed; docs/validation.md reports it.
  EXPECT_NEAR(whole_ratio, 1, 0.12);
}

// How high a 6 cm block (216 particles, E = 0.1 MPa) dropped from 10 cm leaves the floor again
// (m; the contacts have no restitution, so any bounce is the block's own elastic energy), with
// `plasticity` its JSON entry ("" for the elastic solid).
Real rebound_of_dropped_block(const std::string& plasticity) {
  Scene scene = load_scene_text(R"({"name": "bounce", "settings": {"solver": "xpbi", "dt": 0.005, "substeps": 20, "iterations": 5},
      "objects": [{"name": "ground", "kind": "collider", "shape": {"type": "plane"}, "friction": 0.5},
                  {"name": "block", "kind": "continuum", "blocks": [{"min": [-0.03, 0.1, -0.03], "max": [0.03, 0.16, 0.03]}],
                   "spacing": 0.01, "density": 1000, "youngs_modulus": 1e5, "poisson_ratio": 0.3)" +
                                    plasticity + "}]}",
                                "bounce");
  const Real r = scene.model.continuum.spacing;
  auto gap = [&] {
    Real lowest = 1e9;
    for (const Vec3& x : scene.state.position) lowest = std::min(lowest, x.y());
    return lowest - r / 2;
  };
  Real rebound = 0;
  bool landed = false;
  for (int k = 0; k < 100; ++k) {  // 0.5 s: it lands at 0.14 s and the bounce peaks by 0.3 s
    step(scene);
    if (gap() < 1e-4) landed = true;
    if (landed) rebound = std::max(rebound, gap());
  }
  return rebound;
}

// The Deborah number De = lambda / t_c decides (t_c the impact's duration, about the time an
// elastic wave takes to cross the block and back, 2 x 6 cm / sqrt(E / rho) = 12 ms): at De = 80
// (lambda = 1 s) the stress has no time to relax and the block bounces as the elastic one does;
// at De = 0.08 (lambda = 1 ms, a liquid of 38 Pa s) it relaxes during the impact and the block
// splashes without leaving the floor.
TEST(XpbiMaxwell, ItBouncesWhenTheImpactIsQuickAndSplashesWhenItIsSlow) {
  const Real elastic = rebound_of_dropped_block("");
  const Real putty = rebound_of_dropped_block(R"(, "plasticity": {"model": "maxwell", "relaxation_time": 1})");
  const Real liquid = rebound_of_dropped_block(R"(, "plasticity": {"model": "maxwell", "relaxation_time": 0.001})");
  fmt::print("dropped block's rebound: elastic {:.4f} m, Maxwell lambda = 1 s {:.4f} m, lambda = 1 ms {:.5f} m\n", elastic,
             putty, liquid);
  // The relaxation over the 12 ms impact at De = 80 removes about t_c / lambda = 1.2 % of the
  // stress; 10 % allows for the bounce's sensitivity to how the block lands.
  EXPECT_GT(elastic, 0.01);
  EXPECT_NEAR(putty / elastic, 1, 0.1);
  // At De = 0.08 the rebound is below a twentieth of the elastic one: the block does not bounce.
  EXPECT_LT(liquid, 0.05 * elastic);
}

}  // namespace
}  // namespace moreau
