#pragma once
// The mean-dilatation element (Nagtegaal, Parks & Rice 1974, CMAME 4; Simo, Taylor & Pister 1985,
// CMAME 51, whose three-field Hu-Washizu element with a constant pressure and dilatation per
// cell it equals for this energy): a locking-free quad4/hex8 for nearly incompressible solids.
//
// The Neo-Hookean energy splits as W = W_rest(C) + U(J), W_rest = mu/2 (tr C - 3) - mu ln J,
// U = lambda/2 (ln J)^2. Only U stiffens without bound as nu -> 1/2, and full integration of it
// forces J = 1 at every quadrature point: more constraints than a bilinear field can meet
// (volumetric locking). The cell's energy instead evaluates U once, at the cell's mean
// dilatation theta = v / V = sum_q w_q J_q / V (V = sum_q w_q its reference volume):
//   Pi_e = sum_q w_q W_rest(E_q) + V U(theta),
// one volume constraint per cell. It is a potential, so
//   f = sum_q w_q B_q^T (S_rest,q + p J_q C_q^-1),                 p = U'(theta),
//   K = sum_q w_q [B_q^T (CC_rest,q + p J_q (C^-1 (x) C^-1 - 2 II_C^-1)) B_q + geometric(S_q)]
//       + U''(theta) / V  b b^T,                                     b = sum_q w_q B_q^T J_q C_q^-1,
// symmetric. A homogeneous deformation has theta = J at every point, so the element passes the
// patch test and equals the displacement element there.
//
// Energy-momentum steps: Gonzalez's discrete gradient (as in solid_element_step), taken per point
// for W_rest and for the cell as a whole for V U(theta), a function of all its points' strains:
// with E_avg = (E_n + E_n+1)/2, dE = E_n+1 - E_n per point and the inner product
// <A, B> = sum_q w_q A_q : B_q,
//   S_vol,q = p(theta(E_avg)) J_q(E_avg) C_q^-1(E_avg) + kappa dE_q,
//   kappa = (V U(theta_n+1) - V U(theta_n) - <S_vol(E_avg), dE>) / <dE, dE>,
// so that <S_vol, dE> = V (U(theta_n+1) - U(theta_n)) exactly, and S_vol is symmetric (angular
// momentum is kept). Its tangent in u_n+1 is exact (derivation in the .cpp). The midpoint rule
// evaluates the static force at u_n+1/2.
#include "moreau/fem/solids/solid_element.hpp"

namespace moreau {

/// The mean-dilatation cell (Neo-Hookean): energy, force and, if asked, tangent at u.
void mean_dilatation_element(const HyperelasticMaterial& material, const CellQuadrature& q, int dim, const Real* u,
                             bool with_tangent, ElementOutput& out);

/// The mean-dilatation cell's force over a step from u_n to u_n+1 (see solid_element_step), the
/// energy at n+1 and, if asked, the tangent d f / d u_n+1.
void mean_dilatation_element_step(const HyperelasticMaterial& material, const CellQuadrature& q, int dim,
                                  const Real* u_n, const Real* u_next, StepRule rule, bool with_tangent,
                                  ElementOutput& out);

}  // namespace moreau
