// XPBI's continuum with plasticity off is an elastic StVK-Hencky solid: a block dropped on the
// floor bounces and never gains energy, and a cube under a known load holds the strain the
// StVK-Hencky law gives for that load.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "moreau/continuum/plastic_flow.hpp"
#include "moreau/model/diagnostics.hpp"
#include "moreau/scene/scene.hpp"

namespace moreau {
namespace {

void step(Scene& scene) {
  StageTimer timer;
  scene.formulation->step(scene.model, scene.state, timer, 1);
}

Real total_energy(const Scene& scene) {
  return kinetic_energy(scene.model, scene.state, -1) + potential_energy(scene.model, scene.state, -1) +
         elastic_energy(scene.model, scene.state, -1);
}

Real lowest_particle(const Scene& scene) {
  Real lowest = 1e9;
  for (const Vec3& x : scene.state.position) lowest = std::min(lowest, x.y());
  return lowest;
}

// A 6 cm elastic block dropped from 10 cm onto the floor: the contacts have no restitution, so
// the bounce is the block's own elastic energy given back. Energy conservation bounds the
// discrete scheme from above: kinetic + gravitational + elastic energy never exceeds its start.
TEST(XpbiElastic, ADroppedBlockBouncesAndNeverGainsEnergy) {
  Scene scene = load_scene_text(R"({"name": "bounce", "settings": {"solver": "xpbi", "dt": 0.005, "substeps": 20, "iterations": 5},
      "objects": [{"name": "ground", "kind": "collider", "shape": {"type": "plane"}, "friction": 0.5},
                  {"name": "block", "kind": "continuum", "blocks": [{"min": [-0.03, 0.1, -0.03], "max": [0.03, 0.16, 0.03]}],
                   "spacing": 0.01, "density": 1000, "youngs_modulus": 1e5, "poisson_ratio": 0.3}]})",
                                "bounce");
  const Real r = scene.model.continuum.spacing;
  const Real start = total_energy(scene), drop = lowest_particle(scene) - r / 2;
  Real most = start, rebound = 0;
  bool landed = false;
  for (int k = 0; k < 200; ++k) {  // 1 s
    step(scene);
    most = std::max(most, total_energy(scene));
    const Real gap = lowest_particle(scene) - r / 2;
    if (gap < 1e-4) landed = true;
    if (landed) rebound = std::max(rebound, gap);  // how high it leaves the floor again
  }
  fmt::print("dropped block: most energy {:.6f} of the start, rebound {:.4f} m of a {:.3f} m drop, at rest {:.4f} of the start\n",
             most / start, rebound, drop, total_energy(scene) / start);
  // The scheme may only lose energy (impact, XSPH, the position-level steps): 1e-6 of the start
  // allows round-off of the sums and nothing more.
  EXPECT_LE(most / start, 1 + 1e-6);
  // It bounces: the lowest particles leave the floor again, by a quarter of the drop (0.28 of it
  // measured: the rest goes into the block's vibration and is damped).
  EXPECT_GT(rebound / drop, 0.2);
}

// The StVK-Hencky law in uniaxial stress (frictionless faces): tau_yy = E eps, eps = ln of the
// stretch, the lateral logarithmic strains -nu eps, J = exp((1 - 2 nu) eps). The Cauchy stress
// tau_yy / J acts on the current cross-section A0 exp(-2 nu eps), so a cube of initial section
// A0 carries the load  N = -A0 E eps exp(-eps).
Real hencky_uniaxial_load(Real A0, Real E, Real eps) { return -A0 * E * eps * std::exp(-eps); }

// An 8 cm cube of 512 particles under a 1.6 kg plate on a damped prismatic guide, every contact
// frictionless: it settles to about 18 % compression, where the StVK-Hencky law's load is 22 %
// above the linear E eps A0.
TEST(XpbiElastic, ACompressedCubeCarriesTheStVKHenckyStress) {
  const Real E = 1e4, nu = 0.3, density = 100, plate = 1.6, side = 0.08;
  Scene scene = load_scene_text(R"({"name": "cube", "settings": {"solver": "xpbi", "dt": 0.005, "substeps": 10, "iterations": 5},
      "objects": [{"name": "ground", "kind": "collider", "shape": {"type": "plane"}, "friction": 0},
                  {"name": "cube", "kind": "continuum", "blocks": [{"min": [-0.04, 0, -0.04], "max": [0.04, 0.08, 0.04]}],
                   "spacing": 0.01, "density": 100, "youngs_modulus": 1e4, "poisson_ratio": 0.3, "friction": 0},
                  {"name": "plate", "kind": "rigid_body", "shape": {"type": "box", "half_extents": [0.06, 0.01, 0.06]},
                   "position": [0, 0.09, 0], "mass": 1.6, "friction": 0}],
      "joints": [{"name": "guide", "type": "prismatic", "bodies": ["world", "plate"], "anchor": [0, 0.09, 0],
                  "axis": [0, 1, 0], "damping": 20}]})",
                                "cube");
  const ContinuumModel& c = scene.model.continuum;
  const Real r = c.spacing;
  std::vector<Vec3> rest(c.size());
  for (Index i = 0; i < c.size(); ++i) rest[i] = scene.state.position[c.particle[i]];
  for (int k = 0; k < 400; ++k) step(scene);  // 2 s: the guide's damping settles the plate within 1 s

  // The load at mid-height: the plate and the upper half of the cube.
  const Real load = 9.81 * (plate + density * side * side * side / 2), A0 = side * side;
  // The strain the material holds: the mean logarithmic strain ln(F)_yy of the particles two
  // layers or more from the top and bottom faces (the middle half of the cube).
  Real held = 0;
  int middle = 0;
  for (Index i = 0; i < c.size(); ++i) {
    if (rest[i].y() < 2 * r || rest[i].y() > side - 2 * r) continue;
    const RotationSvd F = rotation_svd(scene.state.continuum.deformation[i]);
    held += (F.U * F.sigma.array().log().matrix().asDiagonal() * F.U.transpose())(1, 1);
    ++middle;
  }
  held /= middle;
  // The strain the particles' positions show: mean heights of the layers 2 r above the bottom
  // and 2 r below the top, and the mean widths of the columns 1 r inside the side faces.
  auto layer_mean = [&](int axis, Real at) {
    Real sum = 0;
    int count = 0;
    for (Index i = 0; i < c.size(); ++i)
      if (std::abs(rest[i][axis] - at) < 1e-9) sum += scene.state.position[c.particle[i]][axis], ++count;
    return sum / count;
  };
  auto strain_between = [&](int axis, Real a, Real b) { return std::log((layer_mean(axis, b) - layer_mean(axis, a)) / (b - a)); };
  const Real placed = strain_between(1, 2.5 * r, side - 2.5 * r);
  const Real lateral = strain_between(0, -side / 2 + r / 2, side / 2 - r / 2);
  const Real whole = strain_between(1, r / 2, side - r / 2);
  const Real law_held = hencky_uniaxial_load(A0, E, held), law_placed = hencky_uniaxial_load(A0, E, placed);
  fmt::print("compressed cube: load {:.4f} N; held strain {:.5f} (law's load {:+.2f} %), strain of the middle layers' "
             "positions {:.5f} ({:+.2f} %), of the whole cube's {:.5f} ({:+.2f} %); lateral / axial {:.4f}\n",
             load, held, 100 * (law_held / load - 1), placed, 100 * (law_placed / load - 1), whole,
             100 * (hencky_uniaxial_load(A0, E, whole) / load - 1), lateral / whole);
  // The issue's bound: the stress the law gives for the strain the material holds is the load's
  // within 2 % (0.2 % measured; linear elasticity at that strain would be 18 % short).
  EXPECT_NEAR(law_held / load, 1, 0.02);
  // The particles' positions agree less: the deformation gradients follow the kernel-averaged
  // velocity gradient, which at the faces sees one-sided neighbourhoods, and the middle layers'
  // spacing is 4 % short of the held strain (the whole cube's, including the faces, 10 %). These
  // bounds keep that from growing unnoticed; docs/validation.md reports it.
  EXPECT_NEAR(law_placed / load, 1, 0.06);
  // Poisson's ratio from the positions: -lateral / axial = nu (0.290 measured).
  EXPECT_NEAR(-lateral / whole, nu, 0.05 * nu);
}

}  // namespace
}  // namespace moreau
