#pragma once
// Measurements of settled particle fluids that the tests of each formulation share: the resting
// tank's pressure profile and a floating slab's draft.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "fluid_test_helpers.hpp"
#include "test_helpers.hpp"

namespace moreau::test {

/// A tank of water at rest: 0.15 x 0.15 m base, 0.2 m of water, r = 6.25 mm: 12 x 16 x 12 = 2304
/// particles, 16 layers deep (the free surface settles by about half a particle radius, so the
/// height error is ~ r / (2 H): 1.5 % here, 3 % at half this resolution), under `settings`.
inline std::string resting_tank_scene(const std::string& settings) {
  return R"({"name": "rest", "settings": )" + settings + R"(,
    "objects": [
      {"name": "tank", "kind": "collider", "inside": true,
       "shape": {"type": "box", "center": [0, 0.25, 0], "half_extents": [0.075, 0.25, 0.075]}},
      {"name": "water", "kind": "fluid", "particle_radius": 0.00625,
       "block": {"min": [-0.075, 0, -0.075], "max": [0.075, 0.2, 0.075]}}]})";
}

/// A blob of water thrown at 1.5 m/s at a free box, off its centre line, without gravity (no walls:
/// every row is internal to fluid and box), under `settings`.
inline std::string blob_hits_box_scene(const std::string& settings) {
  return R"({"name": "hit", "settings": )" + settings + R"(,
    "objects": [
      {"name": "water", "kind": "fluid", "particle_radius": 0.005, "velocity": [1.5, 0.2, 0],
       "block": {"min": [-0.1, -0.01, -0.03], "max": [-0.04, 0.05, 0.03]}},
      {"name": "box", "kind": "rigid_body", "shape": {"type": "box", "half_extents": [0.04, 0.04, 0.04]},
       "position": [0.04, 0, 0], "density": 800}]})";
}

/// The resting tank's pressure against depth: slope dp/dy (Pa/m), the fit's R^2 and the height
/// where the fitted pressure vanishes (m).
struct PressureProfile {
  Real slope, r2, surface;
};

/// Steps the resting tank `samples` more times and fits its pressure profile. A single particle's
/// pressure jitters from step to step (the unilateral constraint switches off whenever C < 0), so
/// the profile is the mean pressure of each 2r-thick layer over those steps, fitted by least
/// squares. Only the inner columns count (more than h = 4r from the side walls): next to a wall a
/// particle's pressure also carries the wall's share. Layers within h of the floor or the surface
/// are left out.
inline PressureProfile fit_tank_pressure(Scene& scene, int samples) {
  const FluidState& f = scene.state.fluid;
  const Real r = 0.00625, d = 2 * r;
  const int layers = 12;  // layer centres 0.03125 ... 0.16875 m
  std::vector<Real> layer_sum(layers, 0.0), layer_y(layers, 0.0);
  std::vector<long> layer_count(layers, 0);
  for (int sample = 0; sample < samples; ++sample) {
    run_steps(scene, 1);
    for (Index i = 0; i < f.count; ++i) {
      const Vec3& x = f.position[i];
      const int k = static_cast<int>(std::floor((x.y() - 4 * r) / d));
      if (std::abs(x.x()) > 0.075 - 4 * r || std::abs(x.z()) > 0.075 - 4 * r || k < 0 || k >= layers) continue;
      layer_sum[k] += f.pressure[i], layer_y[k] += x.y(), ++layer_count[k];
    }
  }
  Real sy = 0, sp = 0, syy = 0, syp = 0, spp = 0;
  for (int k = 0; k < layers; ++k) {
    const Real y = layer_y[k] / layer_count[k], p = layer_sum[k] / layer_count[k];
    std::printf("layer y = %.4f m: p = %.1f Pa (hydrostatic %.1f)\n", y, p, 9810 * (0.2 - y));
    sy += y, sp += p, syy += y * y, syp += y * p, spp += p * p;
  }
  const Real cov = layers * syp - sy * sp, var_y = layers * syy - sy * sy, var_p = layers * spp - sp * sp;
  const Real slope = cov / var_y;
  return {slope, cov * cov / (var_y * var_p), (sp - slope * sy) / layers / -slope};
}

/// A floating slab (a rigid body named "slab", 0.06 m high, in the slab-flotation tank): its
/// draft, open-water surface minus its bottom face averaged over 0.3 s after 1.2 s of settling,
/// and its largest tilt over that time (degrees). 4 ms steps.
struct Flotation {
  Real draft, tilt;
};
inline Flotation measure_flotation(Scene& scene) {
  const Index body = scene.model.objects[scene.model.find_object("slab")].body;
  run_steps(scene, 300);
  Flotation result{0, 0};
  const int samples = 75;
  for (int k = 0; k < samples; ++k) {
    run_steps(scene, 1);
    const Real bottom = scene.state.rigid.position[body].y() - 0.03;
    result.draft += (slab_tank_open_surface(scene.state.fluid) - bottom) / samples;
    const Vec3 up = scene.state.rigid.orientation[body] * Vec3::UnitY();
    result.tilt = std::max(result.tilt, std::acos(std::min<Real>(1, up.y())) * 180 / kPi);
  }
  return result;
}

}  // namespace moreau::test
