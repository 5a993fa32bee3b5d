#pragma once
// Measurements of particle fluids shared by the fluid tests.
#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>

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

/// Two blobs of water (rho 1000 and 800, viscosities mu_a and mu_b, no XSPH) in free space, 6^3
/// particles each (r = 1 cm), flying at each other at 1 m/s off-centre; dt = 2 ms in 4 substeps.
/// `fluid_settings` is the JSON of settings.fluid ("{}" for the defaults).
inline std::string colliding_blobs_scene(Real mu_a, Real mu_b, const std::string& fluid_settings = "{}") {
  return fmt::format(R"({{"name": "blobs", "settings": {{"dt": 0.002, "substeps": 4, "gravity": [0, 0, 0], "fluid": {}}},
    "objects": [{{"name": "a", "kind": "fluid", "particle_radius": 0.01, "viscosity": {}, "xsph": 0,
                 "block": {{"min": [-0.2, 0, 0], "max": [-0.08, 0.12, 0.12]}}, "velocity": [1, 0, 0]}},
                {{"name": "b", "kind": "fluid", "particle_radius": 0.01, "viscosity": {}, "xsph": 0, "density": 800,
                 "block": {{"min": [0.08, 0.06, 0], "max": [0.2, 0.18, 0.12]}}, "velocity": [-1, 0, 0]}}]}})",
                     fluid_settings, mu_a, mu_b);
}

/// Per-particle values of the fluid (its positions or velocities) sorted by particle id, as the
/// neighbour search re-sorts the arrays: runs on different thread counts compare entry by entry.
inline std::vector<std::pair<Index, Vec3>> by_particle_id(const FluidState& f, const std::vector<Vec3>& values) {
  std::vector<std::pair<Index, Vec3>> out;
  for (Index i = 0; i < f.count; ++i) out.emplace_back(f.id[i], values[i]);
  std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  return out;
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

/// Start-up plane Couette flow between a still wall at x = 0 and one sliding along y at U from
/// t = 0 at x = H, for a liquid of kinematic viscosity nu at rest before (a Fourier sine series):
///   u(x, t) = U x / H - sum_n 2 U / (n pi) (-1)^(n+1) sin(n pi x / H) exp(-n^2 pi^2 nu t / H^2).
inline Real couette_startup_speed(Real x, Real t, Real U, Real H, Real nu) {
  Real u = U * x / H;
  for (int n = 1; n < 2000; ++n)
    u -= 2 * U / (n * kPi) * (n % 2 == 1 ? 1 : -1) * std::sin(n * kPi * x / H) * std::exp(-n * n * kPi * kPi * nu * t / (H * H));
  return u;
}

/// The mean speed along y of the particles of each of `layers` slices of [0, H] in x, taking only
/// the particles with y in [y_low, y_high], and each slice's mean x. A slice without particles has
/// count 0.
struct SliceSpeeds {
  std::vector<Real> speed, x;
  std::vector<int> count;
};

inline SliceSpeeds slice_speeds(const FluidState& f, Real H, int layers, Real y_low, Real y_high) {
  SliceSpeeds s{std::vector<Real>(layers, 0), std::vector<Real>(layers, 0), std::vector<int>(layers, 0)};
  for (Index i = 0; i < f.count; ++i) {
    const Vec3& p = f.position[i];
    if (p.y() < y_low || p.y() > y_high) continue;
    const int layer = std::clamp(static_cast<int>(p.x() / H * layers), 0, layers - 1);
    s.speed[layer] += f.velocity[i].y();
    s.x[layer] += p.x();
    ++s.count[layer];
  }
  for (int k = 0; k < layers; ++k)
    if (s.count[k] > 0) s.speed[k] /= s.count[k], s.x[k] /= s.count[k];
  return s;
}

/// A 4 cm gap of mu = 10 Pa s liquid (r = 2 mm, 10 particles across, x in [0, 0.04], y in
/// [0.3, 0.5], z in [0, 0.024]) in a free-slip tank, no gravity, dt = 1/120 s in 10 substeps. The
/// wall at x = 0 is a collider of fluid friction `still_friction` (JSON number), the tank's friction
/// against bodies is `tank_friction`; `wall` is the JSON object of the other side's wall.
inline std::string viscous_gap_scene(const std::string& wall, const std::string& still_friction = "1",
                                     const std::string& tank_friction = "0.5") {
  return R"({"name": "gap", "settings": {"dt": 0.008333333333333333, "substeps": 10, "gravity": [0, 0, 0]},
    "objects": [
      {"name": "box", "kind": "collider", "inside": true, "friction": )" + tank_friction + R"(,
       "shape": {"type": "box", "center": [0.02, 0.3, 0.012], "half_extents": [0.03, 0.4, 0.012]}},
      {"name": "still", "kind": "collider", "fluid_friction": )" + still_friction + R"(,
       "shape": {"type": "box", "center": [-0.005, 0.3, 0.012], "half_extents": [0.005, 0.4, 0.03]}},
      )" + wall + R"(,
      {"name": "liquid", "kind": "fluid", "particle_radius": 0.002, "viscosity": 10, "xsph": 0,
       "block": {"min": [0, 0.3, 0], "max": [0.04, 0.5, 0.024]}}]})";
}

}  // namespace moreau::test
