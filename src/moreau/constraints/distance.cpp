#include "moreau/constraints/distance.hpp"

#include <cmath>

namespace moreau {

void DistanceConstraints::color(const std::vector<Real>& particle_inv_mass) {
  std::vector<std::array<Index, 4>> stencils;
  stencils.reserve(size());
  for (const auto& p : particles) stencils.push_back({p[0], p[1], -1, -1});
  const auto permutation = color_constraints(stencils, particle_inv_mass, batches);
  apply_permutation_to_all(permutation, particles, rest_length, compliance, damping_time, object);
}

DistanceConstraints::Rows DistanceConstraints::rows(Index k, const Vec3* x) const {
  const auto [a, b] = particles[k];
  const DistanceValue v = evaluate_distance(x[a], x[b], rest_length[k]);
  Rows r;
  r.particle = {a, b};
  r.C(0) = v.C;
  r.gradient = {v.grad0.transpose(), -v.grad0.transpose()};
  r.compliance(0, 0) = compliance[k];
  r.damping_time = damping_time[k];
  return r;
}

Real DistanceConstraints::energy(const Vec3* x, Index of_object) const {
  Real energy = 0;
  for (size_t k = 0; k < size(); ++k) {
    if ((of_object >= 0 && object[k] != of_object) || compliance[k] <= 0) continue;
    const Real C = evaluate_distance(x[particles[k][0]], x[particles[k][1]], rest_length[k]).C;
    energy += 0.5 * C * C / compliance[k];
  }
  return energy;
}

Real DistanceConstraints::max_error(const Vec3* x, Index of_object) const {
  Real error = 0;
  for (size_t k = 0; k < size(); ++k) {
    if (of_object >= 0 && object[k] != of_object) continue;
    error = std::max(error, std::abs(evaluate_distance(x[particles[k][0]], x[particles[k][1]], rest_length[k]).C));
  }
  return error;
}

}  // namespace moreau
