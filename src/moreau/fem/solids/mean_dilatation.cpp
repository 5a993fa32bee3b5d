#include "moreau/fem/solids/mean_dilatation.hpp"

#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "moreau/fem/solids/solid_element_kernels.hpp"

namespace moreau {

namespace {

constexpr int kMaxPoints = 8;  // the stiffness rule of a hex8 cell, 2 x 2 x 2

// The volume change of a cell at a set of point strains: per point J - 1 and C^-1, and the cell's
// reference volume V and mean dilatation theta - 1 = sum_q w_q (J_q - 1) / V.
struct CellDilatation {
  std::array<Real, kMaxPoints> J{};
  std::array<Mat3, kMaxPoints> C_inverse{};
  Real volume = 0, theta_minus_one = 0;
  bool valid = true;
};

void check_points(const CellQuadrature& q) {
  if (q.points > kMaxPoints) throw std::logic_error("mean dilatation: more quadrature points than a hex8 cell has");
}

CellDilatation dilatation(const CellQuadrature& q, const Mat3* E) {
  CellDilatation d;
  for (int p = 0; p < q.points; ++p) {
    // J - 1 = sqrt(1 + (det C - 1)) - 1, with det C - 1 expanded for its digits.
    const Real detC_minus_one = det_identity_plus_minus_one(2 * E[p]);
    if (!(detC_minus_one > -1)) {
      d.valid = false;
      return d;
    }
    const Real J_minus_one = detC_minus_one / (1 + std::sqrt(1 + detC_minus_one));
    d.J[p] = 1 + J_minus_one;
    d.C_inverse[p] = (Mat3::Identity() + 2 * E[p]).inverse();
    d.volume += q.weight[p];
    d.theta_minus_one += q.weight[p] * J_minus_one;
  }
  d.theta_minus_one /= d.volume;
  d.valid = d.theta_minus_one > -1;
  return d;
}

// V U(theta) of a cell, +infinity where undefined.
Real volumetric_energy(const HyperelasticMaterial& material, const CellDilatation& d) {
  return d.valid ? d.volume * material.volumetric_energy(d.theta_minus_one).energy
                 : std::numeric_limits<Real>::infinity();
}

}  // namespace

void mean_dilatation_element(const HyperelasticMaterial& material, const CellQuadrature& q, int dim, const Real* u,
                             bool with_tangent, ElementOutput& out) {
  check_points(q);
  const int n = q.nodes * dim;
  start_output(n, with_tangent, out);
  const HyperelasticMaterial rest = material.without_volumetric_energy();
  std::array<Mat3, kMaxPoints> F, E;
  for (int p = 0; p < q.points; ++p) {
    const Mat3 H = displacement_gradient(q.gradient + static_cast<size_t>(p) * q.nodes, q.nodes, dim, u);
    F[p] = Mat3::Identity() + H;
    if (!(F[p].determinant() > 0)) return mark_inverted(out);
    E[p] = green_lagrange_strain(H);
  }
  const CellDilatation d = dilatation(q, E.data());
  if (!d.valid) return mark_inverted(out);
  const HyperelasticMaterial::Volumetric U = material.volumetric_energy(d.theta_minus_one);
  out.energy = d.volume * U.energy;
  StrainMatrix B;
  ElementVector b = ElementVector::Zero(n);  // sum_q w_q B_q^T J_q C_q^-1 = d(V theta)/du
  for (int p = 0; p < q.points; ++p) {
    const Vec3* G = q.gradient + static_cast<size_t>(p) * q.nodes;
    const Real w = q.weight[p];
    const HyperelasticResponse r = rest.respond(E[p], with_tangent);
    if (!r.valid) return mark_inverted(out);
    out.energy += w * r.energy;
    const Vec6 JC_inverse = d.J[p] * to_voigt(d.C_inverse[p]);
    const Vec6 S = r.stress + U.pressure * JC_inverse;
    strain_displacement(F[p], G, q.nodes, dim, B);
    out.force.noalias() += w * B.transpose() * S;
    if (!with_tangent) continue;
    add_tangent(B, B, r.tangent + pressure_stress_tangent(d.C_inverse[p], U.pressure * d.J[p]), S, G, q.nodes, dim, w,
                out.tangent);
    b.noalias() += w * B.transpose() * JC_inverse;
  }
  if (with_tangent) out.tangent.noalias() += (U.stiffness / d.volume) * b * b.transpose();
}

// Energy-momentum tangent (header for the force). With, per point q, t_q = J C^-1 and
// s_q = p t_q at E_avg (p = U'(theta_avg), k = U''(theta_avg)), P_q = d s_q / dE at fixed p,
// s1_q the same stress at E_n+1, e_q = dE_q (tensor components), gamma_q its engineering form,
// D = <dE, dE> = sum w e . gamma, N = V U_n+1 - V U_n - sum w s . gamma, kappa = N / D, and
// dgamma1_q = B_q(F_n+1) du_n+1 (d E_avg = dE_n+1 / 2):
//   ds_r     = P_r dgamma1_r / 2 + (k / V) t_r sum_q w_q t_q . dgamma1_q / 2,
//   dkappa   = sum_q w_q g_q . dgamma1_q / D,
//   g_q      = s1_q - s_q - P_q gamma_q / 2 - (k / V) T t_q / 2 - 2 kappa e_q,   T = sum_r w_r t_r . gamma_r,
//   dS_vol,r = ds_r + e_r dkappa + kappa II dgamma1_r,
// and f = sum_r w_r B_r(F_mid)^T S_r gives
//   K = sum_r w_r B_r^T (CC_rest,r + P_r + 2 kappa II) B1_r / 2 + geometric(S_r) / 2
//       + (k / 2V) (sum_r w_r B_r^T t_r)(sum_q w_q B1_q^T t_q)^T + (sum_r w_r B_r^T e_r)(sum_q w_q B1_q^T g_q)^T / D.
void mean_dilatation_element_step(const HyperelasticMaterial& material, const CellQuadrature& q, int dim,
                                  const Real* u_n, const Real* u_next, StepRule rule, bool with_tangent,
                                  ElementOutput& out) {
  check_points(q);
  const int n = q.nodes * dim;
  if (rule == StepRule::midpoint) {
    // The static force at u_n+1/2 (d u_n+1/2 / d u_n+1 = 1/2); the energy at u_n+1.
    ElementVector u_mid(n);
    for (int i = 0; i < n; ++i) u_mid[i] = 0.5 * (u_n[i] + u_next[i]);
    ElementOutput end;
    mean_dilatation_element(material, q, dim, u_next, false, end);
    mean_dilatation_element(material, q, dim, u_mid.data(), with_tangent, out);
    if (!end.valid || !out.valid) return mark_inverted(out);
    out.energy = end.energy;
    if (with_tangent) out.tangent *= 0.5;
    return;
  }
  start_output(n, with_tangent, out);
  const HyperelasticMaterial rest = material.without_volumetric_energy();
  std::array<Mat3, kMaxPoints> F_mid, F_next, E_n, E_next, E_avg;
  for (int p = 0; p < q.points; ++p) {
    const Vec3* G = q.gradient + static_cast<size_t>(p) * q.nodes;
    const Mat3 H0 = displacement_gradient(G, q.nodes, dim, u_n), H1 = displacement_gradient(G, q.nodes, dim, u_next);
    F_mid[p] = Mat3::Identity() + 0.5 * (H0 + H1);
    F_next[p] = Mat3::Identity() + H1;
    if (!(F_next[p].determinant() > 0) || !(F_mid[p].determinant() > 0)) return mark_inverted(out);
    E_n[p] = green_lagrange_strain(H0);
    E_next[p] = green_lagrange_strain(H1);
    E_avg[p] = 0.5 * (E_n[p] + E_next[p]);
  }
  const CellDilatation d_n = dilatation(q, E_n.data()), d_next = dilatation(q, E_next.data()),
                       d_avg = dilatation(q, E_avg.data());
  if (!d_n.valid || !d_next.valid || !d_avg.valid) return mark_inverted(out);
  const Real V = d_avg.volume;
  const HyperelasticMaterial::Volumetric U_avg = material.volumetric_energy(d_avg.theta_minus_one),
                                         U_next = material.volumetric_energy(d_next.theta_minus_one);
  // kappa: the cell's discrete-gradient correction.
  std::array<Vec6, kMaxPoints> t, s, e, gamma;
  Real D = 0, sum_s_gamma = 0, T = 0;
  for (int p = 0; p < q.points; ++p) {
    t[p] = d_avg.J[p] * to_voigt(d_avg.C_inverse[p]);
    s[p] = U_avg.pressure * t[p];
    e[p] = to_voigt(E_next[p] - E_n[p]);
    gamma[p] = e[p];
    gamma[p].tail<3>() *= 2;
    D += q.weight[p] * e[p].dot(gamma[p]);
    sum_s_gamma += q.weight[p] * s[p].dot(gamma[p]);
    T += q.weight[p] * t[p].dot(gamma[p]);
  }
  const Real energy_next = V * U_next.energy;
  const bool corrected = D > 1e-16 * V;
  const Real kappa = corrected ? (energy_next - volumetric_energy(material, d_n) - sum_s_gamma) / D : 0;
  out.energy = energy_next;
  StrainMatrix B, B_next;
  ElementVector a1, c1, a2, c2;
  if (with_tangent) {
    a1.setZero(n);
    c1.setZero(n);
    a2.setZero(n);
    c2.setZero(n);
  }
  const Vec6 shear_half = (Vec6() << 1, 1, 1, 0.5, 0.5, 0.5).finished();
  for (int p = 0; p < q.points; ++p) {
    const Vec3* G = q.gradient + static_cast<size_t>(p) * q.nodes;
    const Real w = q.weight[p];
    const PointDiscreteGradient r = discrete_gradient(rest, E_n[p], E_next[p], with_tangent);
    if (!r.valid) return mark_inverted(out);
    out.energy += w * r.energy;
    const Vec6 S = r.stress + s[p] + kappa * e[p];
    strain_displacement(F_mid[p], G, q.nodes, dim, B);
    out.force.noalias() += w * B.transpose() * S;
    if (!with_tangent) continue;
    strain_displacement(F_next[p], G, q.nodes, dim, B_next);
    const Mat6 P = pressure_stress_tangent(d_avg.C_inverse[p], U_avg.pressure * d_avg.J[p]);
    Mat6 CC = r.tangent + P;
    CC.diagonal() += 2 * kappa * shear_half;
    add_tangent(B, B_next, CC, S, G, q.nodes, dim, 0.5 * w, out.tangent);
    a1.noalias() += w * B.transpose() * t[p];
    c1.noalias() += w * B_next.transpose() * t[p];
    if (!corrected) continue;
    const Vec6 s_next = U_next.pressure * d_next.J[p] * to_voigt(d_next.C_inverse[p]);
    const Vec6 g = s_next - s[p] - 0.5 * P * gamma[p] - (0.5 * U_avg.stiffness * T / V) * t[p] - 2 * kappa * e[p];
    a2.noalias() += w * B.transpose() * e[p];
    c2.noalias() += w * B_next.transpose() * g;
  }
  if (!with_tangent) return;
  out.tangent.noalias() += (0.5 * U_avg.stiffness / V) * a1 * c1.transpose();
  if (corrected) out.tangent.noalias() += (1 / D) * a2 * c2.transpose();
}

}  // namespace moreau
