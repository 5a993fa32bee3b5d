#pragma once
// Measurements of particle fluids shared by the fluid tests.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "moreau/fluids/fluid_state.hpp"

namespace moreau::test {

/// The free surface of fluid in a square tank |x|, |z| <= half: the top (centre + r) of the highest
/// particle of each 2r-wide lattice column, then the median over the columns holding particles
/// that `keep(x)` accepts. The median ignores a stray particle hopping on the surface.
template <class Keep>
Real median_column_top(const FluidState& f, Real half, Real r, Keep&& keep) {
  const Real d = 2 * r;
  const int columns = static_cast<int>(std::floor(2 * half / d + 1e-9));
  std::vector<Real> top(columns * columns, -1.0);
  for (Index i = 0; i < f.count; ++i) {
    const Vec3& x = f.position[i];
    if (!keep(x)) continue;
    const int cx = std::clamp(static_cast<int>((x.x() + half) / d), 0, columns - 1);
    const int cz = std::clamp(static_cast<int>((x.z() + half) / d), 0, columns - 1);
    top[cz * columns + cx] = std::max(top[cz * columns + cx], x.y() + r);
  }
  top.erase(std::remove(top.begin(), top.end(), -1.0), top.end());
  std::nth_element(top.begin(), top.begin() + top.size() / 2, top.end());
  return top[top.size() / 2];
}

inline Real median_column_top(const FluidState& f, Real half, Real r) {
  return median_column_top(f, half, r, [](const Vec3&) { return true; });
}

/// The slab-flotation scene: 0.1 m of water (r = 6.25 mm, 2,888 particles) in a 0.24 m square
/// tank, dt = 4 ms in 8 substeps, and `slab`, the JSON object of the floating body (named "slab").
inline std::string slab_tank_scene(const std::string& slab) {
  return R"({"name": "slab", "settings": {"dt": 0.004, "substeps": 8, "iterations": 1},
    "objects": [
      {"name": "tank", "kind": "collider", "inside": true,
       "shape": {"type": "box", "center": [0, 0.2, 0], "half_extents": [0.12, 0.2, 0.12]}},
      {"name": "water", "kind": "fluid", "particle_radius": 0.00625,
       "block": {"min": [-0.12, 0, -0.12], "max": [0.12, 0.1, 0.12]}},
      )" + slab + "]}";
}

/// The free surface of the slab-flotation tanks (0.24 m square, r = 6.25 mm) away from a floating
/// slab: the median column top over the outer ring |x| or |z| >= 0.09 m, 3 cm clear of it.
inline Real slab_tank_open_surface(const FluidState& f) {
  return median_column_top(f, 0.12, 0.00625,
                           [](const Vec3& x) { return std::max(std::abs(x.x()), std::abs(x.z())) >= 0.09; });
}

}  // namespace moreau::test
