#include "moreau/constraints/neo_hookean_tet.hpp"

#include <cmath>

#include "moreau/constraints/tet_kinematics.hpp"

namespace moreau {

void NeoHookeanTetConstraints::add(const std::array<Index, 4>& tet, const std::array<Vec3, 4>& rest,
                                   Real youngs_modulus, Real poisson_ratio, Real tau, Index obj) {
  const Mat3 Dm = tet_edge_matrix(rest);
  const Mat3 B = Dm.inverse();
  const Real volume = Dm.determinant() / 6;
  const Real mu = youngs_modulus / (2 * (1 + poisson_ratio));
  const Real lambda_lame = youngs_modulus * poisson_ratio / ((1 + poisson_ratio) * (1 - 2 * poisson_ratio));
  const Real lambda = lambda_lame + mu;  // the stable Neo-Hookean lambda (see the header)
  elements.push_back({tet, B * B.transpose(), 1 / (6 * volume), 1 / (lambda * volume), 1 / (mu * volume),
                      1 + mu / lambda, tau});
  rest_inverse.push_back(B);
  object.push_back(obj);
}

void NeoHookeanTetConstraints::color(const std::vector<Real>& particle_inv_mass) {
  std::vector<std::array<Index, 4>> stencils;
  for (const auto& e : elements) stencils.push_back(e.particles);
  const auto permutation = color_constraints(stencils, particle_inv_mass, batches);
  apply_permutation_to_all(permutation, elements, rest_inverse, object);
}

namespace {
inline std::array<Vec3, 4> gather(const Vec3* x, const std::array<Index, 4>& p) { return {x[p[0]], x[p[1]], x[p[2]], x[p[3]]}; }
}  // namespace

NeoHookeanTetConstraints::Rows NeoHookeanTetConstraints::rows(Index k, const Vec3* x) const {
  const NeoHookeanElement& e = elements[k];
  const NeoHookeanValue v = evaluate_neo_hookean(gather(x, e.particles), e);
  Rows r;
  r.particle = e.particles;
  r.C = Vec2(v.C_H, v.C_D);
  for (int i = 0; i < 4; ++i) {
    r.gradient[i].row(0) = v.grad_H[i].transpose();
    r.gradient[i].row(1) = v.grad_D[i].transpose();
  }
  r.compliance.diagonal() = Vec2(e.compliance_H, e.compliance_D);
  r.damping_time = e.damping_time;
  return r;
}

Real NeoHookeanTetConstraints::energy(const Vec3* x, Index of_object) const {
  // V Psi = (mu V/2)(|F|^2 - 3) + (lambda V/2)(det F - gamma)^2 with mu V = 1/alpha_D and
  // lambda V = 1/alpha_H; the rest value (lambda V/2)(1 - gamma)^2 is subtracted.
  Real energy = 0;
  for (size_t k = 0; k < size(); ++k) {
    if (of_object >= 0 && object[k] != of_object) continue;
    const NeoHookeanElement& e = elements[k];
    const NeoHookeanValue v = evaluate_neo_hookean(gather(x, e.particles), e);
    const Real rest_H = 1 - e.gamma;
    energy += 0.5 * (v.C_D * v.C_D - 3) / e.compliance_D + 0.5 * (v.C_H * v.C_H - rest_H * rest_H) / e.compliance_H;
  }
  return energy;
}

Real NeoHookeanTetConstraints::max_error(const Vec3* x, Index of_object) const {
  Real error = 0;
  for (size_t k = 0; k < size(); ++k) {
    if (of_object >= 0 && object[k] != of_object) continue;
    const NeoHookeanElement& e = elements[k];
    const Real det_F = evaluate_neo_hookean(gather(x, e.particles), e).C_H + e.gamma;
    error = std::max(error, std::abs(det_F - 1));
  }
  return error;
}

}  // namespace moreau
