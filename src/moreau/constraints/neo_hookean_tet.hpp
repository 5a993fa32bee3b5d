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
// lambda = lambda_Lame + mu reproduces linear elasticity with E and nu (derivation in
// docs/methods/neo-hookean.md; checked by the hanging-bar test).
// The pair is solved per element as a coupled 2x2 system in (dlambda_H, dlambda_D), whose
// off-diagonal sum_i w_i grad_i C_H . grad_i C_D removes the fight between the two near rest.
#include <vector>

#include "moreau/constraints/constraint_batches.hpp"
#include "moreau/constraints/xpbd_update.hpp"

namespace moreau {

/// What one element's projection reads, packed into 128 bytes (built by color()).
struct NeoHookeanElement {
  std::array<Index, 4> particles;
  Mat3 rest_metric;                // M = B B^T with B = D_m^-1, 1/m^2
  Real inv_rest_det;               // 1 / det D_m = 1 / (6 V), 1/m^3
  Real compliance_H;               // 1/(lambda V), 1/J
  Real compliance_D;               // 1/(mu V), 1/J
  Real gamma;                      // 1 + mu/lambda
  Real damping_time;               // s
};

struct NeoHookeanTetConstraints {
  std::vector<std::array<Index, 4>> particles;
  std::vector<Mat3> rest_inverse;      // D_m^-1, 1/m
  std::vector<Real> rest_volume;       // m^3
  std::vector<Real> mu;                // Pa
  std::vector<Real> lambda;            // Pa (the stable Neo-Hookean lambda = lambda_Lame + mu)
  std::vector<Real> damping_time;      // s
  std::vector<Index> object;
  ColorBatches batches;
  std::vector<NeoHookeanElement> packed;  // colour-sorted copy of the above for the projection loop

  size_t size() const { return particles.size(); }
  void add(const std::array<Index, 4>& tet, const std::array<Vec3, 4>& rest, Real youngs_modulus, Real poisson_ratio,
           Real tau, Index obj);
  /// Sorts the elements by colour and builds `packed`; call after the last add().
  void color(const std::vector<Real>& particle_inv_mass);
};

struct NeoHookeanValue {
  Real C_H, C_D;
  std::array<Vec3, 4> grad_H, grad_D;
};

NeoHookeanValue evaluate_neo_hookean(const std::array<Vec3, 4>& x, const Mat3& rest_inverse, Real gamma);

/// lambda holds two multipliers per element: (H, D).
void project_neo_hookean(const NeoHookeanTetConstraints& c, Vec2* lambda, const SubstepContext& s);

/// Strain energy V (Psi(F) - Psi(I)), J.
Real neo_hookean_energy(const NeoHookeanTetConstraints& c, const Vec3* x, Index object);

/// max |det F - 1| (relative volume error) over the elements of `object`.
Real neo_hookean_max_volume_error(const NeoHookeanTetConstraints& c, const Vec3* x, Index object);

}  // namespace moreau
