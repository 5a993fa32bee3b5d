#include "moreau/constraints/neo_hookean_tet.hpp"

#include <cmath>

#include "moreau/constraints/tet_kinematics.hpp"

namespace moreau {

void NeoHookeanTetConstraints::add(const std::array<Index, 4>& tet, const std::array<Vec3, 4>& rest,
                                   Real youngs_modulus, Real poisson_ratio, Real tau, Index obj) {
  Mat3 Dm;
  Dm.col(0) = rest[1] - rest[0];
  Dm.col(1) = rest[2] - rest[0];
  Dm.col(2) = rest[3] - rest[0];
  const Real m = youngs_modulus / (2 * (1 + poisson_ratio));
  const Real lambda_lame = youngs_modulus * poisson_ratio / ((1 + poisson_ratio) * (1 - 2 * poisson_ratio));
  particles.push_back(tet);
  rest_inverse.push_back(Dm.inverse());
  rest_volume.push_back(Dm.determinant() / 6.0);
  mu.push_back(m);
  lambda.push_back(lambda_lame + m);
  damping_time.push_back(tau);
  object.push_back(obj);
}

void NeoHookeanTetConstraints::color(const std::vector<Real>& particle_inv_mass) {
  const auto permutation = color_constraints(particles, particle_inv_mass, batches);
  apply_permutation(particles, permutation);
  apply_permutation(rest_inverse, permutation);
  apply_permutation(rest_volume, permutation);
  apply_permutation(mu, permutation);
  apply_permutation(lambda, permutation);
  apply_permutation(damping_time, permutation);
  apply_permutation(object, permutation);
}

NeoHookeanValue evaluate_neo_hookean(const std::array<Vec3, 4>& x, const Mat3& rest_inverse, Real gamma) {
  const Mat3 F = tet_deformation_gradient(x[0], x[1], x[2], x[3], rest_inverse);
  NeoHookeanValue v;
  v.C_H = F.determinant() - gamma;
  v.grad_H = tet_vertex_gradients(cofactor(F), rest_inverse);
  v.C_D = F.norm();
  const Mat3 dD = v.C_D > 0 ? Mat3(F / v.C_D) : Mat3::Zero();
  v.grad_D = tet_vertex_gradients(dD, rest_inverse);
  return v;
}

void project_neo_hookean(const NeoHookeanTetConstraints& c, Vec2* lambda, const SubstepContext& s) {
  const Real inv_h2 = 1.0 / (s.h * s.h);
  for_each_by_color(c.batches, [&](Index k) {
    const auto& p = c.particles[k];
    const std::array<Vec3, 4> x{s.x[p[0]], s.x[p[1]], s.x[p[2]], s.x[p[3]]};
    const Real gamma_snh = 1 + c.mu[k] / c.lambda[k];
    const NeoHookeanValue v = evaluate_neo_hookean(x, c.rest_inverse[k], gamma_snh);
    // Coupled 2x2 XPBD system in (dlambda_H, dlambda_D):
    //   [(1+g) J W J^T + diag(alpha~_H, alpha~_D)] dl = -(C + alpha~ lambda + g J dx)
    Real hh = 0, hd = 0, dd = 0, Jdx_H = 0, Jdx_D = 0;
    for (int i = 0; i < 4; ++i) {
      const Real w = s.inv_mass[p[i]];
      hh += w * v.grad_H[i].squaredNorm();
      hd += w * v.grad_H[i].dot(v.grad_D[i]);
      dd += w * v.grad_D[i].squaredNorm();
      const Vec3 dx = x[i] - s.x_start[p[i]];
      Jdx_H += v.grad_H[i].dot(dx);
      Jdx_D += v.grad_D[i].dot(dx);
    }
    const Real alpha_H = inv_h2 / (c.lambda[k] * c.rest_volume[k]);
    const Real alpha_D = inv_h2 / (c.mu[k] * c.rest_volume[k]);
    const Real g = c.damping_time[k] / s.h;
    Mat2 A;
    A << (1 + g) * hh + alpha_H, (1 + g) * hd, (1 + g) * hd, (1 + g) * dd + alpha_D;
    const Vec2 rhs(-(v.C_H + alpha_H * lambda[k].x() + g * Jdx_H), -(v.C_D + alpha_D * lambda[k].y() + g * Jdx_D));
    const Real det = A.determinant();
    if (!(std::abs(det) > 0)) return;  // all four vertices fixed, or a degenerate element
    const Vec2 dl(( A(1, 1) * rhs.x() - A(0, 1) * rhs.y()) / det, (-A(1, 0) * rhs.x() + A(0, 0) * rhs.y()) / det);
    lambda[k] += dl;
    for (int i = 0; i < 4; ++i) s.x[p[i]] += s.inv_mass[p[i]] * (dl.x() * v.grad_H[i] + dl.y() * v.grad_D[i]);
  });
}

Real neo_hookean_energy(const NeoHookeanTetConstraints& c, const Vec3* x, Index object) {
  Real energy = 0;
  for (size_t k = 0; k < c.size(); ++k) {
    if (object >= 0 && c.object[k] != object) continue;
    const auto& p = c.particles[k];
    const Mat3 F = tet_deformation_gradient(x[p[0]], x[p[1]], x[p[2]], x[p[3]], c.rest_inverse[k]);
    const Real gamma = 1 + c.mu[k] / c.lambda[k];
    const Real psi = 0.5 * c.mu[k] * (F.squaredNorm() - 3) + 0.5 * c.lambda[k] * std::pow(F.determinant() - gamma, 2);
    const Real psi_rest = 0.5 * c.lambda[k] * std::pow(1 - gamma, 2);
    energy += c.rest_volume[k] * (psi - psi_rest);
  }
  return energy;
}

Real neo_hookean_max_volume_error(const NeoHookeanTetConstraints& c, const Vec3* x, Index object) {
  Real error = 0;
  for (size_t k = 0; k < c.size(); ++k) {
    if (object >= 0 && c.object[k] != object) continue;
    const auto& p = c.particles[k];
    const Mat3 F = tet_deformation_gradient(x[p[0]], x[p[1]], x[p[2]], x[p[3]], c.rest_inverse[k]);
    error = std::max(error, std::abs(F.determinant() - 1));
  }
  return error;
}

}  // namespace moreau
