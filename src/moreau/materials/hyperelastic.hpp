#pragma once
// Hyperelastic materials written in the Green-Lagrange strain E = (C - I)/2, C = F^T F, shared by
// the FEM engine (total-Lagrangian elements, energy-momentum integration) and, later, the
// constraint engine. Each model gives the stored energy W per reference volume, the second
// Piola-Kirchhoff stress S = dW/dE = 2 dW/dC and the material tangent CC = dS/dE.
//
// Compressible Neo-Hookean (e.g. Bonet & Wood, Nonlinear Continuum Mechanics, ch. 6):
//   W = mu/2 (tr C - 3) - mu ln J + lambda/2 (ln J)^2,       J = sqrt(det C)
//   S = mu (I - C^-1) + lambda ln J C^-1
//   CC_IJKL = lambda C^-1_IJ C^-1_KL + (mu - lambda ln J)(C^-1_IK C^-1_JL + C^-1_IL C^-1_JK)
// St. Venant-Kirchhoff:
//   W = lambda/2 (tr E)^2 + mu E:E,   S = lambda tr E I + 2 mu E,   CC = lambda I(x)I + 2 mu II_sym
// Both reduce to linear elasticity with Lame's lambda and mu at E = 0. Plane strain uses the same
// formulas with E_33 = E_13 = E_23 = 0.
// Why E and not C: at small strains C - I and ln det C lose the digits of the strain to
// cancellation (a strain of 1e-5 keeps 11). Here I - C^-1 = 2 C^-1 E and ln J = log1p(det C - 1)/2
// with det(I + 2E) - 1 expanded in the invariants of 2E, so the stress is accurate to round-off
// at any strain, which Newton's convergence on stiff or lightly loaded bodies needs.
//
// Voigt order used for stresses and the tangent: (11, 22, 33, 12, 23, 13); strains in Voigt form
// carry engineering shears (2 E_12, ...), so S_v . dE_v = S : dE.
#include <Eigen/Dense>

#include "moreau/math/types.hpp"

namespace moreau {

using Vec6 = Eigen::Matrix<Real, 6, 1>;
using Mat6 = Eigen::Matrix<Real, 6, 6>;

struct LameParameters {
  Real lambda = 0, mu = 0;  // Pa
};

/// lambda = E nu / ((1 + nu)(1 - 2 nu)), mu = E / (2 (1 + nu)); E > 0, -1 < nu < 1/2.
LameParameters lame_from_youngs(Real youngs_modulus, Real poisson_ratio);

enum class HyperelasticModel { neo_hookean, st_venant_kirchhoff };

/// The stress and tangent at one strain; `valid` is false where W is undefined (Neo-Hookean, det C <= 0).
struct HyperelasticResponse {
  Real energy = 0;       // J/m^3
  Vec6 stress;           // S in Voigt order, Pa
  Mat6 tangent;          // CC in Voigt order, Pa
  bool valid = true;
};

struct HyperelasticMaterial {
  HyperelasticModel model = HyperelasticModel::neo_hookean;
  LameParameters lame;
  Real density = 0;  // kg/m^3 (reference configuration)

  /// W(E); +infinity where undefined.
  Real energy(const Mat3& E) const;
  /// S(E) as a symmetric matrix.
  Mat3 stress(const Mat3& E) const;
  /// W, S and, if `with_tangent`, CC at the Green-Lagrange strain E.
  HyperelasticResponse respond(const Mat3& E, bool with_tangent = true) const;

  // The Neo-Hookean energy split W = W_rest(C) + U(J), U(J) = lambda/2 (ln J)^2, for elements that
  // evaluate U at a cell's mean J (mean dilatation). Neo-Hookean only.
  /// The material without U: lambda = 0, so respond() gives W_rest = mu/2 (tr C - 3) - mu ln J.
  HyperelasticMaterial without_volumetric_energy() const;
  /// U(J) and its derivatives dU/dJ, d2U/dJ2, from J - 1 (kept apart for its digits).
  struct Volumetric {
    Real energy = 0, pressure = 0, stiffness = 0;
  };
  Volumetric volumetric_energy(Real J_minus_one) const;
};

/// det(I + X) - 1 = tr X + ((tr X)^2 - tr X^2)/2 + det X, without cancellation for small X.
Real det_identity_plus_minus_one(const Mat3& X);

/// d(J C^-1)/dE scaled by p: p J (C^-1 (x) C^-1 - 2 II_C^-1) in Voigt order (the tangent of the
/// stress p J C^-1 of a pressure p held fixed), with II_C^-1_IJKL = (C^-1_IK C^-1_JL + C^-1_IL C^-1_JK)/2.
Mat6 pressure_stress_tangent(const Mat3& C_inverse, Real pJ);

/// The Green-Lagrange strain of F = I + H without forming C - I: E = (H + H^T + H^T H)/2.
Mat3 green_lagrange_strain(const Mat3& H);

/// A symmetric 3x3 matrix in Voigt order (no factor 2 on the shears).
Vec6 to_voigt(const Mat3& A);
Mat3 from_voigt(const Vec6& v);

}  // namespace moreau
