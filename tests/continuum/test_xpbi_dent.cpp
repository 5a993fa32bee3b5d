// A rigid sphere pressed into a von Mises slab leaves a dent that stays: after the sphere is
// withdrawn the slab springs back only by the elastic part of the indentation, which contact
// mechanics bounds, while the same slab without plasticity springs back flat.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "moreau/scene/scene.hpp"

namespace moreau {
namespace {

constexpr Real kSpacing = 0.005;        // m, r
constexpr Real kSlabHalfWidth = 0.05;   // m
constexpr Real kSlabHeight = 0.04;      // m
constexpr Real kSphereRadius = 0.03;    // m
constexpr Real kPressSpeed = 0.05;      // m/s
constexpr Real kPressTime = 0.2;        // s: the sphere goes 1 cm down, then is withdrawn at once
constexpr Real kYoungsModulus = 2e5;    // Pa
constexpr Real kPoissonRatio = 0.3;
constexpr Real kYieldStress = 2000;     // Pa: sigma_Y / E = 1 %

Scene dent_scene(bool plastic) {
  const std::string plasticity =
      plastic ? fmt::format(R"(, "plasticity": {{"model": "von_mises", "yield_stress": {}}})", kYieldStress) : "";
  return load_scene_text(
      fmt::format(R"({{"name": "dent", "settings": {{"solver": "xpbi", "dt": 0.005, "substeps": 10, "iterations": 5}},
        "objects": [{{"name": "floor", "kind": "collider", "shape": {{"type": "plane"}}, "friction": 0.5}},
          {{"name": "sphere", "kind": "collider", "shape": {{"type": "sphere", "center": [0, {}, 0], "radius": {}}},
            "velocity": [0, {}, 0], "until": {}, "friction": 0}},
          {{"name": "slab", "kind": "continuum", "blocks": [{{"min": [{}, 0, {}], "max": [{}, {}, {}]}}], "spacing": {},
            "density": 1000, "youngs_modulus": {}, "poisson_ratio": {}, "friction": 0.5{}}}]}})",
                  kSlabHeight + kSphereRadius, kSphereRadius, -kPressSpeed, kPressTime, -kSlabHalfWidth,
                  -kSlabHalfWidth, kSlabHalfWidth, kSlabHeight, kSlabHalfWidth, kSpacing, kYoungsModulus,
                  kPoissonRatio, plasticity),
      "dent");
}

void run(Scene& scene, Real duration) {
  StageTimer timer;
  const long steps = std::lround(duration / scene.model.settings.dt);
  for (long k = 0; k < steps; ++k) scene.formulation->step(scene.model, scene.state, timer, 1);
}

// The dent's depth: how far the highest particle on the sphere's axis lies below the slab's top
// far from the sphere (the mean height of the top layer's particles along the slab's edges).
Real dent_depth(const Scene& scene) {
  Real axis_top = -1, edge_top = 0, highest = -1;
  int edge_count = 0;
  for (const Vec3& x : scene.state.position) highest = std::max(highest, x.y());
  for (const Vec3& x : scene.state.position) {
    const Real rho = std::hypot(x.x(), x.z());
    if (rho < 0.75 * kSpacing) axis_top = std::max(axis_top, x.y());
    if (rho > kSlabHalfWidth - 1.5 * kSpacing && x.y() > highest - kSpacing / 2) edge_top += x.y(), ++edge_count;
  }
  return edge_top / edge_count - axis_top;
}

struct Indentation {
  Real loaded;    // m, the dent under the sphere just before it is withdrawn
  Real residual;  // m, the dent 0.1 s after, averaged over its last 0.05 s
};

Indentation indent(bool plastic) {
  Scene scene = dent_scene(plastic);
  run(scene, kPressTime);
  const Real loaded = dent_depth(scene);
  run(scene, 0.05);
  Real residual = 0;
  for (int k = 0; k < 10; ++k) {
    run(scene, 0.005);
    residual += dent_depth(scene) / 10;
  }
  return {loaded, residual};
}

// The elastic part of an indentation (Johnson, Contact Mechanics, 1985, sec. 6.4 and 11.4): the
// unloading is Hertzian, so a contact of radius a under the load P = pi a^2 p_m springs back by
// delta_e = 3 P / (4 E* a) = 3 pi a p_m / (4 E*), E* = E / (1 - nu^2). A fully plastic contact
// carries Tabor's mean pressure p_m of about 2.8 to 3 sigma_Y; p_m = 3 sigma_Y bounds it. With the
// sphere 1 cm deep (a = 2.2 cm) that is 1.4 mm.
TEST(XpbiDent, ASpherePressedIntoPlasticineLeavesADentThatStays) {
  const Indentation dent = indent(true);
  const Real a = std::sqrt(2 * kSphereRadius * dent.loaded - dent.loaded * dent.loaded);
  const Real springback_bound =
      3 * M_PI * a * (3 * kYieldStress) * (1 - kPoissonRatio * kPoissonRatio) / (4 * kYoungsModulus);
  const Real springback = dent.loaded - dent.residual;
  fmt::print("von Mises slab: dent {:.2f} mm under the sphere, {:.2f} mm after it left; springback {:.2f} mm, "
             "Hertzian unloading from Tabor's pressure at most {:.2f} mm\n",
             1e3 * dent.loaded, 1e3 * dent.residual, 1e3 * springback, 1e3 * springback_bound);
  // The sphere went 1 cm down; the particles under it follow it to within a lattice spacing.
  EXPECT_NEAR(dent.loaded, kPressSpeed * kPressTime, kSpacing);
  EXPECT_GT(springback, 0);
  EXPECT_LT(springback, springback_bound);
}

// The control: without plasticity the same slab is an elastic solid and its top comes back flat,
// to within 5 % of the dent (what is left of its ringing 0.1 s after the sphere left).
TEST(XpbiDent, AnElasticSlabSpringsBackFlat) {
  const Indentation dent = indent(false);
  fmt::print("elastic slab: dent {:.2f} mm under the sphere, {:.3f} mm after it left\n", 1e3 * dent.loaded,
             1e3 * dent.residual);
  EXPECT_NEAR(dent.loaded, kPressSpeed * kPressTime, kSpacing);
  EXPECT_LT(std::abs(dent.residual), 0.05 * dent.loaded);
}

}  // namespace
}  // namespace moreau
