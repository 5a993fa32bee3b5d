#include "moreau/constraints/distance.hpp"

#include <cmath>

namespace moreau {

void DistanceConstraints::color(const std::vector<Real>& particle_inv_mass) {
  std::vector<std::array<Index, 4>> stencils;
  stencils.reserve(size());
  for (const auto& p : particles) stencils.push_back({p[0], p[1], -1, -1});
  const auto permutation = color_constraints(stencils, particle_inv_mass, batches);
  apply_permutation(particles, permutation);
  apply_permutation(rest_length, permutation);
  apply_permutation(compliance, permutation);
  apply_permutation(damping_time, permutation);
  apply_permutation(object, permutation);
}

DistanceValue evaluate_distance(const Vec3& x0, const Vec3& x1, Real rest_length) {
  const Vec3 d = x0 - x1;
  const Real length = d.norm();
  const Vec3 n = length > 0 ? Vec3(d * (1 / length)) : Vec3::Zero();
  return {length - rest_length, n};
}

void project_distance(const DistanceConstraints& c, Real* lambda, const SubstepContext& s) {
  for_each_by_color(c.batches, [&](Index k) {
    const auto [a, b] = c.particles[k];
    const Real wa = s.inv_mass[a], wb = s.inv_mass[b];
    const auto [C, n] = evaluate_distance(s.x[a], s.x[b], c.rest_length[k]);
    const Real tau = c.damping_time[k];
    const Real grad_dot_dx = tau > 0 ? n.dot((s.x[a] - s.x_start[a]) - (s.x[b] - s.x_start[b])) : 0;
    const Real dl = xpbd_delta_lambda(C, lambda[k], c.compliance[k], tau, s, wa + wb, grad_dot_dx);
    lambda[k] += dl;
    s.x[a] += (wa * dl) * n;
    s.x[b] -= (wb * dl) * n;
  });
}

Real distance_energy(const DistanceConstraints& c, const Vec3* x, Index object) {
  Real energy = 0;
  for (size_t k = 0; k < c.size(); ++k) {
    if ((object >= 0 && c.object[k] != object) || c.compliance[k] <= 0) continue;
    const Real C = evaluate_distance(x[c.particles[k][0]], x[c.particles[k][1]], c.rest_length[k]).C;
    energy += 0.5 * C * C / c.compliance[k];
  }
  return energy;
}

Real distance_max_error(const DistanceConstraints& c, const Vec3* x, Index object) {
  Real error = 0;
  for (size_t k = 0; k < c.size(); ++k) {
    if (object >= 0 && c.object[k] != object) continue;
    error = std::max(error, std::abs(evaluate_distance(x[c.particles[k][0]], x[c.particles[k][1]], c.rest_length[k]).C));
  }
  return error;
}

}  // namespace moreau
