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
  apply_permutation(hinges, permutation);
  apply_permutation(edge_length, permutation);
  apply_permutation(object, permutation);
}

Vec3 isometric_bending_value(const IsometricHinge& h, const Vec3* x) {
  const auto& p = h.particles;
  const auto& K = h.weight;
  return K[0] * x[p[0]] + K[1] * x[p[1]] + K[2] * x[p[2]] + K[3] * x[p[3]];
}

void project_isometric_bending(const IsometricBendingConstraints& c, Vec3* lambda, const SubstepContext& s) {
  for_each_by_color(c.batches, [&](Index k) {
    const IsometricHinge& h = c.hinges[k];
    const auto& p = h.particles;
    const auto& K = h.weight;
    const std::array<Real, 4> w{s.inv_mass[p[0]], s.inv_mass[p[1]], s.inv_mass[p[2]], s.inv_mass[p[3]]};
    const Vec3 C = isometric_bending_value(h, s.x);
    // XPBD with grad_i C = K_i I: the 3x3 system matrix is ((1+g) sum_i w_i K_i^2 + alpha~) I.
    const Real alpha_tilde = h.compliance * s.inv_h2;
    const Real g = h.damping_time * s.inv_h;
    Vec3 rhs = -(C + alpha_tilde * lambda[k]);
    if (g > 0) {
      Vec3 J_dx = Vec3::Zero();
      for (int i = 0; i < 4; ++i) J_dx += K[i] * (s.x[p[i]] - s.x_start[p[i]]);
      rhs -= g * J_dx;
    }
    const Real denominator =
        (1 + g) * (w[0] * K[0] * K[0] + w[1] * K[1] * K[1] + w[2] * K[2] * K[2] + w[3] * K[3] * K[3]) + alpha_tilde;
    if (!(denominator > 0)) return;
    const Vec3 dl = rhs * (1 / denominator);
    lambda[k] += dl;
    for (int i = 0; i < 4; ++i) s.x[p[i]] += (w[i] * K[i]) * dl;
  });
}

Real isometric_bending_energy(const IsometricBendingConstraints& c, const Vec3* x, Index object) {
  Real energy = 0;
  for (size_t k = 0; k < c.size(); ++k) {
    if ((object >= 0 && c.object[k] != object) || c.hinges[k].compliance <= 0) continue;
    energy += 0.5 * isometric_bending_value(c.hinges[k], x).squaredNorm() / c.hinges[k].compliance;
  }
  return energy;
}

Real isometric_bending_max_error(const IsometricBendingConstraints& c, const Vec3* x, Index object) {
  Real error = 0;
  for (size_t k = 0; k < c.size(); ++k) {
    if (object >= 0 && c.object[k] != object) continue;
    error = std::max(error, isometric_bending_value(c.hinges[k], x).norm() / c.edge_length[k]);
  }
  return error;
}

}  // namespace moreau
