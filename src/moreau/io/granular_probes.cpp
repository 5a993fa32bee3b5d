#include "moreau/io/granular_probes.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "moreau/model/diagnostics.hpp"

namespace moreau {

namespace {

// Calls f(mass, position, velocity, radius) for the particles of `object` (or of every object,
// -1), fluid particles included.
template <class F>
void for_each_particle(const Model& model, const State& state, Index object, F&& f) {
  for_each_live_particle(model, state, object, [&](Index p) {
    f(model.particle_mass[p], state.position[p], state.velocity[p], model.particle_radius[p]);
  });
  const FluidState& fluid = state.fluid;
  for_each_fluid_particle(model, state, object, [&](Index i) {
    f(fluid.mass[i], fluid.position[i], fluid.velocity[i], model.fluid.particle_radius);
  });
}

}  // namespace

Vec3 up_direction(const Model& model) {
  const Vec3& g = model.settings.gravity;
  return g.norm() > 0 ? Vec3(-g.normalized()) : Vec3::UnitY();
}

Real angle_of_repose(const Model& model, const State& state, Index object, const std::optional<Vec3>& axis_point,
                     Real bin, const std::optional<std::pair<Vec3, Vec3>>& region, Real resting_speed) {
  constexpr Real kNan = std::numeric_limits<Real>::quiet_NaN();
  const Vec3 up = up_direction(model);
  auto counted = [&](const Vec3& x, const Vec3& v) {
    if (resting_speed > 0 && v.squaredNorm() >= resting_speed * resting_speed) return false;
    return !region || ((x.array() >= region->first.array()).all() && (x.array() <= region->second.array()).all());
  };
  Vec3 axis = Vec3::Zero();
  Real mass = 0, base = std::numeric_limits<Real>::infinity();
  for_each_particle(model, state, object, [&](Real m, const Vec3& x, const Vec3& v, Real r) {
    if (!counted(x, v)) return;
    axis += m * x;
    mass += m;
    base = std::min(base, x.dot(up) - r);
  });
  if (!(mass > 0)) return kNan;
  axis = axis_point.value_or(axis / mass);

  // Surface height of each ring: its highest particle top above the pile's bottom.
  std::vector<Real> surface;
  for_each_particle(model, state, object, [&](Real, const Vec3& x, const Vec3& v, Real r) {
    if (!counted(x, v)) return;
    const Vec3 d = x - axis;
    const Real rho = (d - d.dot(up) * up).norm();
    constexpr Real kMostRings = 1e6;  // a grain flung far away does not size the rings
    if (!(rho / bin < kMostRings)) return;
    const size_t ring = static_cast<size_t>(rho / bin);
    if (ring >= surface.size()) surface.resize(ring + 1, -1);
    surface[ring] = std::max(surface[ring], x.dot(up) + r - base);
  });
  const Real peak = *std::max_element(surface.begin(), surface.end());

  // Least-squares line h = a + s rho through the flank's rings (rho at the ring's centre).
  Real n = 0, sum_rho = 0, sum_h = 0, sum_rho2 = 0, sum_rho_h = 0;
  for (size_t k = 0; k < surface.size(); ++k) {
    if (surface[k] < 0.2 * peak || surface[k] > 0.8 * peak) continue;
    const Real rho = (k + 0.5) * bin, h = surface[k];
    n += 1;
    sum_rho += rho;
    sum_h += h;
    sum_rho2 += rho * rho;
    sum_rho_h += rho * h;
  }
  if (n < 3) return kNan;
  const Real slope = (n * sum_rho_h - sum_rho * sum_h) / (n * sum_rho2 - sum_rho * sum_rho);
  return std::atan(-slope) * 180 / kPi;
}

Real runout(const Model& model, const State& state, Index object, const std::optional<Vec3>& axis_point,
            const std::optional<Vec3>& direction, Real fraction) {
  const Vec3 up = up_direction(model);
  const Vec3 axis = axis_point ? *axis_point : center_of_mass(model, state, object);
  std::vector<Real> reach;
  for_each_particle(model, state, object, [&](Real, const Vec3& x, const Vec3&, Real r) {
    const Vec3 d = x - axis;
    reach.push_back((direction ? d.dot(*direction) : (d - d.dot(up) * up).norm()) + r);
  });
  if (reach.empty()) return std::numeric_limits<Real>::quiet_NaN();
  // The k-th smallest with k = ceil(fraction n): the share `fraction` lies within it.
  const size_t k = std::max<size_t>(1, static_cast<size_t>(std::ceil(fraction * reach.size() - 1e-9))) - 1;
  std::nth_element(reach.begin(), reach.begin() + k, reach.end());
  return reach[k];
}

Real mass_flow_rate(const Model& model, const State& state, Index object, const Vec3& point, const Vec3& n) {
  Real delta = 0;
  for_each_particle(model, state, object, [&](Real, const Vec3&, const Vec3&, Real r) { delta = std::max(delta, r); });
  if (!(delta > 0)) return 0;
  Real flux = 0;
  for_each_particle(model, state, object, [&](Real m, const Vec3& x, const Vec3& v, Real) {
    if (std::abs((x - point).dot(n)) < delta) flux += m * v.dot(n);
  });
  return flux / (2 * delta);
}

Real mass_beyond(const Model& model, const State& state, Index object, const Vec3& point, const Vec3& n) {
  Real mass = 0;
  for_each_particle(model, state, object, [&](Real m, const Vec3& x, const Vec3&, Real) {
    if ((x - point).dot(n) > 0) mass += m;
  });
  return mass;
}

}  // namespace moreau
