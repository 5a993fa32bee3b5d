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
  packed.clear();
  for (size_t k = 0; k < size(); ++k)
    packed.push_back({particles[k], rest_inverse[k] * rest_inverse[k].transpose(),
                      1 / (6 * rest_volume[k]), 1 / (lambda[k] * rest_volume[k]), 1 / (mu[k] * rest_volume[k]),
                      1 + mu[k] / lambda[k], damping_time[k]});
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
  for_each_by_color(c.batches, [&](Index k) {
    const NeoHookeanElement& e = c.packed[k];
    const auto& p = e.particles;
    const std::array<Vec3, 4> x{s.x[p[0]], s.x[p[1]], s.x[p[2]], s.x[p[3]]};
    const std::array<Real, 4> w{s.inv_mass[p[0]], s.inv_mass[p[1]], s.inv_mass[p[2]], s.inv_mass[p[3]]};
    // With D_s = [d1 d2 d3] (d_i = x_i - x0), F = D_s B, B = D_m^-1 and M = B B^T:
    //   det F = d1 . (d2 x d3) / det D_m,   grad_1 C_H = (d2 x d3) / det D_m (and cyclic),
    //   |F|^2 = tr(D_s^T D_s M),            [grad_1 C_D grad_2 C_D grad_3 C_D] = D_s M / |F|,
    // with grad_0 = -(grad_1 + grad_2 + grad_3) for both (translation invariance).
    const Vec3 d1 = x[1] - x[0], d2 = x[2] - x[0], d3 = x[3] - x[0];
    const Vec3 c1 = d2.cross(d3), c2 = d3.cross(d1), c3 = d1.cross(d2);
    const Real C_H = d1.dot(c1) * e.inv_rest_det - e.gamma;
    const Mat3& M = e.rest_metric;
    const Vec3 DM1 = M(0, 0) * d1 + M(1, 0) * d2 + M(2, 0) * d3;  // columns of D_s M
    const Vec3 DM2 = M(0, 1) * d1 + M(1, 1) * d2 + M(2, 1) * d3;
    const Vec3 DM3 = M(0, 2) * d1 + M(1, 2) * d2 + M(2, 2) * d3;
    const Real C_D = std::sqrt(d1.dot(DM1) + d2.dot(DM2) + d3.dot(DM3));
    if (!(C_D > 0)) return;  // collapsed to a point: no direction to restore
    const Real inv_C_D = 1 / C_D;
    const std::array<Vec3, 4> gH{-(c1 + c2 + c3) * e.inv_rest_det, c1 * e.inv_rest_det, c2 * e.inv_rest_det,
                                 c3 * e.inv_rest_det};
    const std::array<Vec3, 4> gD{-(DM1 + DM2 + DM3) * inv_C_D, DM1 * inv_C_D, DM2 * inv_C_D, DM3 * inv_C_D};
    // Coupled 2x2 XPBD system in (dlambda_H, dlambda_D):
    //   [(1+g) J W J^T + diag(alpha~_H, alpha~_D)] dl = -(C + alpha~ lambda + g J dx)
    Real hh = 0, hd = 0, dd = 0;
    for (int i = 0; i < 4; ++i) {
      hh += w[i] * gH[i].squaredNorm();
      hd += w[i] * gH[i].dot(gD[i]);
      dd += w[i] * gD[i].squaredNorm();
    }
    const Real alpha_H = e.compliance_H * s.inv_h2, alpha_D = e.compliance_D * s.inv_h2;
    const Real g = e.damping_time * s.inv_h;
    Real Jdx_H = 0, Jdx_D = 0;
    if (g > 0) {
      for (int i = 0; i < 4; ++i) {
        const Vec3 dx = x[i] - s.x_start[p[i]];
        Jdx_H += gH[i].dot(dx);
        Jdx_D += gD[i].dot(dx);
      }
    }
    const Real a = (1 + g) * hh + alpha_H, b = (1 + g) * hd, d = (1 + g) * dd + alpha_D;
    const Real rhs_H = -(C_H + alpha_H * lambda[k].x() + g * Jdx_H);
    const Real rhs_D = -(C_D + alpha_D * lambda[k].y() + g * Jdx_D);
    const Real det = a * d - b * b;
    if (!(std::abs(det) > 0)) return;  // all four vertices fixed, or a degenerate element
    const Real inv_det = 1 / det;
    const Real dl_H = (d * rhs_H - b * rhs_D) * inv_det, dl_D = (a * rhs_D - b * rhs_H) * inv_det;
    lambda[k] += Vec2(dl_H, dl_D);
    for (int i = 0; i < 4; ++i) s.x[p[i]] = x[i] + w[i] * (dl_H * gH[i] + dl_D * gD[i]);
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
