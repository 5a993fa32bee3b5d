// Snow (Stomakhin et al. 2013) under XPBI: a snowball thrown at a wall shatters when its critical
// stretch is small and stays one lump when it is large, the behaviour the parameter exists for.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <algorithm>
#include <numeric>

#include "moreau/scene/scene.hpp"

namespace moreau {
namespace {

// The share of the continuum's particles in its largest piece: particles closer than 1.5 r are
// linked (an intact body's neighbours sit at r, and 1.5 r is the gap a crack must open).
Real largest_piece(const Scene& scene) {
  const ContinuumModel& c = scene.model.continuum;
  const Index n = c.size();
  std::vector<Index> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  auto root = [&](Index i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  const Real link = 1.5 * c.spacing;
  for (Index i = 0; i < n; ++i)
    for (Index j = i + 1; j < n; ++j)
      if ((scene.state.position[c.particle[i]] - scene.state.position[c.particle[j]]).squaredNorm() < link * link)
        parent[root(i)] = root(j);
  std::vector<Index> size(n, 0);
  for (Index i = 0; i < n; ++i) ++size[root(i)];
  return static_cast<Real>(*std::max_element(size.begin(), size.end())) / static_cast<Real>(n);
}

// A snowball 10 cm across (552 particles; Stomakhin et al.'s E = 140 kPa, nu = 0.2, 400 kg/m^3,
// theta_c = 0.025, xi = 10) thrown at 10 m/s at a wall 15 cm away, 0.2 s later.
Real piece_after_impact(Real critical_stretch) {
  Scene scene = load_scene_text(
      fmt::format(R"({{"name": "snowball", "settings": {{"solver": "xpbi", "dt": 0.005, "substeps": 10, "iterations": 5}},
      "objects": [{{"name": "ground", "kind": "collider", "shape": {{"type": "plane"}}, "friction": 0.5}},
                  {{"name": "wall", "kind": "collider", "shape": {{"type": "plane", "normal": [-1, 0, 0], "point": [0.2, 0, 0]}},
                    "friction": 0.5}},
                  {{"name": "snow", "kind": "continuum", "spheres": [{{"center": [0, 0.3, 0], "radius": 0.05}}],
                    "velocity": [10, 0, 0], "spacing": 0.01, "density": 400, "youngs_modulus": 1.4e5, "poisson_ratio": 0.2,
                    "friction": 0.5, "plasticity": {{"model": "snow", "critical_stretch": {}}}}}]}})",
                  critical_stretch),
      "snowball");
  StageTimer timer;
  for (int k = 0; k < 40; ++k) scene.formulation->step(scene.model, scene.state, timer, 1);
  return largest_piece(scene);
}

// theta_s = 0.0025 carries 350 Pa of tension (E theta_s) and the ball shatters: its largest piece keeps 42 %
// of it. theta_s = 0.03 (4.2 kPa, E theta_s, before it flows in tension) holds it in one
// piece that flattens on the wall. The bounds leave room for either to shift by a few particles.
TEST(XpbiSnow, ASnowballShattersOnAWallWhenItsCriticalStretchIsSmall) {
  const Real brittle = piece_after_impact(0.0025), tough = piece_after_impact(0.03);
  fmt::print("largest piece after the impact: {:.3f} (theta_s 0.0025), {:.3f} (theta_s 0.03)\n", brittle, tough);
  EXPECT_LT(brittle, 0.6);
  EXPECT_GT(tough, 0.98);
}

}  // namespace
}  // namespace moreau
