#include "moreau/constraints/isometric_bending.hpp"

#include <cmath>

namespace moreau {

std::array<Real, 4> isometric_hinge_weights(const Vec3& E0, const Vec3& E1, const Vec3& O0, const Vec3& O1) {
  const Vec3 e = E1 - E0;
  const Real l = e.norm();
  const Real area_A = 0.5 * e.cross(O0 - E0).norm(), area_B = 0.5 * (O1 - E0).cross(e).norm();
  const Real k_o0 = l * l / (2 * area_A), k_o1 = l * l / (2 * area_B);
  const Real a0 = (O0 - E0).dot(e) / l, a1 = (O1 - E0).dot(e) / l;
  const Real k_e1 = -(k_o0 * a0 + k_o1 * a1) / l;
  const Real k_e0 = -(k_e1 + k_o0 + k_o1);
  return {k_e0, k_e1, k_o0, k_o1};
}

void IsometricBendingConstraints::add(const Hinge& h, const Vec3& E0, const Vec3& E1, const Vec3& O0, const Vec3& O1,
                                      Real angle_compliance, Real tau, Index obj) {
  const Real l = (E1 - E0).norm();
  hinges.push_back({{h.e0, h.e1, h.o0, h.o1}, isometric_hinge_weights(E0, E1, O0, O1), l * l * angle_compliance, tau});
  edge_length.push_back(l);
  object.push_back(obj);
}

void IsometricBendingConstraints::color(const std::vector<Real>& particle_inv_mass) {
  std::vector<std::array<Index, 4>> stencils;
  for (const auto& h : hinges) stencils.push_back(h.particles);
  const auto permutation = color_constraints(stencils, particle_inv_mass, batches);
  apply_permutation_to_all(permutation, hinges, edge_length, object);
}

IsometricBendingConstraints::Rows IsometricBendingConstraints::rows(Index k, const Vec3* x) const {
  const IsometricHinge& h = hinges[k];
  Rows r;
  r.particle = h.particles;
  r.C = isometric_bending_value(h, x);
  for (int i = 0; i < 4; ++i) r.gradient[i] = h.weight[i] * Mat3::Identity();
  r.compliance = h.compliance * Mat3::Identity();
  r.damping_time = h.damping_time;
  return r;
}

Real IsometricBendingConstraints::energy(const Vec3* x, Index of_object) const {
  Real energy = 0;
  for (size_t k = 0; k < size(); ++k) {
    if ((of_object >= 0 && object[k] != of_object) || hinges[k].compliance <= 0) continue;
    energy += 0.5 * isometric_bending_value(hinges[k], x).squaredNorm() / hinges[k].compliance;
  }
  return energy;
}

Real IsometricBendingConstraints::max_error(const Vec3* x, Index of_object) const {
  Real error = 0;
  for (size_t k = 0; k < size(); ++k) {
    if (of_object >= 0 && object[k] != of_object) continue;
    error = std::max(error, isometric_bending_value(hinges[k], x).norm() / edge_length[k]);
  }
  return error;
}

}  // namespace moreau
