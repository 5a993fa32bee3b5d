#pragma once
// Stable Neo-Hookean tetrahedra as two constraints (Macklin & Mueller 2021, "A Constraint-based
// Formulation of Stable Neo-Hookean Materials", MIG '21).
//
// Energy density (Smith et al. 2018 without the log term):
//   Psi = (mu/2)(tr F^T F - 3) + (lambda/2)(det F - gamma)^2,   gamma = 1 + mu/lambda
// as constraints with per-element compliances (V = rest volume):
//   C_H = det F - gamma,   dC_H/dF = cof F,   alpha_H = 1/(lambda V)     (1/J)
//   C_D = |F|_F,           dC_D/dF = F / C_D, alpha_D = 1/(mu V)         (1/J)
// so that U = C_H^2/(2 alpha_H) + C_D^2/(2 alpha_D) = V Psi + const. At F = I the two forces,
// mu I and lambda(1-gamma) I = -mu I, cancel: the rest state is stable.
// Lame mapping: linearizing Psi about F = I gives mu eps:eps + ((lambda - mu)/2)(tr eps)^2, so
// lambda = lambda_Lame + mu reproduces linear elasticity with E and nu (checked by the
// hanging-bar test).
// The pair is solved per element as a coupled 2x2 system in (dlambda_H, dlambda_D), whose
// off-diagonal sum_i w_i grad_i C_H . grad_i C_D removes the fight between the two near rest.
#include <cmath>
#include <string_view>
#include <vector>

#include "moreau/constraints/constraint_batches.hpp"
#include "moreau/constraints/constraint_rows.hpp"

namespace moreau {

/// One element: everything its projection, energy and error need, packed into 128 bytes.
/// With D_s = [d1 d2 d3] (d_i = x_i - x0), B = D_m^-1, F = D_s B and M = B B^T:
///   det F = d1 . (d2 x d3) / det D_m,   grad_1 C_H = (d2 x d3) / det D_m (and cyclic),
///   |F|^2 = tr(D_s^T D_s M),            [grad_1 C_D grad_2 C_D grad_3 C_D] = D_s M / |F|,
/// with grad_0 = -(grad_1 + grad_2 + grad_3) for both (translation invariance); F is never formed.
struct NeoHookeanElement {
  std::array<Index, 4> particles;
  Mat3 rest_metric;                // M = B B^T, 1/m^2
  Real inv_rest_det;               // 1 / det D_m = 1 / (6 V), 1/m^3
  Real compliance_H;               // alpha_H = 1/(lambda V), 1/J
  Real compliance_D;               // alpha_D = 1/(mu V), 1/J
  Real gamma;                      // 1 + mu/lambda
  Real damping_time;               // s
};

struct NeoHookeanTetConstraints {
  static constexpr std::string_view kName = "neo_hookean", kErrorName = "neo_hookean_volume";
  using Multiplier = Vec2;  // (lambda_H, lambda_D)
  using Rows = RowBlock<4, 2>;

  std::vector<NeoHookeanElement> elements;
  std::vector<Mat3> rest_inverse;  // B = D_m^-1, 1/m: F = D_s B (the velocity-level rows need F itself)
  std::vector<Index> object;
  ColorBatches batches;

  size_t size() const { return elements.size(); }
  void add(const std::array<Index, 4>& tet, const std::array<Vec3, 4>& rest, Real youngs_modulus, Real poisson_ratio,
           Real tau, Index obj);
  void color(const std::vector<Real>& particle_inv_mass);
  /// Rows (C_H, C_D) with compliance diag(alpha_H, alpha_D).
  Rows rows(Index k, const Vec3* x) const;
  /// Strain energy V (Psi(F) - Psi(I)), J.
  Real energy(const Vec3* x, Index object) const;
  /// max |det F - 1| (relative volume error).
  Real max_error(const Vec3* x, Index object) const;
};

struct NeoHookeanValue {
  Real C_H, C_D;
  std::array<Vec3, 4> grad_H, grad_D;  // grad_D is zero when C_D = 0 (element collapsed to a point)
};

/// C_H, C_D and their vertex gradients at positions x (the formulas above).
[[gnu::always_inline]] inline NeoHookeanValue evaluate_neo_hookean(const std::array<Vec3, 4>& x, const NeoHookeanElement& e) {
  const Vec3 d1 = x[1] - x[0], d2 = x[2] - x[0], d3 = x[3] - x[0];
  const Vec3 c1 = d2.cross(d3), c2 = d3.cross(d1), c3 = d1.cross(d2);
  const Mat3& M = e.rest_metric;
  const Vec3 DM1 = M(0, 0) * d1 + M(1, 0) * d2 + M(2, 0) * d3;  // columns of D_s M
  const Vec3 DM2 = M(0, 1) * d1 + M(1, 1) * d2 + M(2, 1) * d3;
  const Vec3 DM3 = M(0, 2) * d1 + M(1, 2) * d2 + M(2, 2) * d3;
  NeoHookeanValue v;
  v.C_H = d1.dot(c1) * e.inv_rest_det - e.gamma;
  v.C_D = std::sqrt(d1.dot(DM1) + d2.dot(DM2) + d3.dot(DM3));
  const Real s = e.inv_rest_det, inv_C_D = v.C_D > 0 ? 1 / v.C_D : 0;
  v.grad_H = {-(c1 + c2 + c3) * s, c1 * s, c2 * s, c3 * s};
  v.grad_D = {-(DM1 + DM2 + DM3) * inv_C_D, DM1 * inv_C_D, DM2 * inv_C_D, DM3 * inv_C_D};
  return v;
}




}  // namespace moreau
