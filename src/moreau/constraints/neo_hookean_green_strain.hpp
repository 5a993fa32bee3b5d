#pragma once
// The stable Neo-Hookean material (neo_hookean_tet.hpp) as Green-strain rows, for a solver that
// linearises its rows once per step (the velocity-level formulation).
//
// The pair (C_H, C_D) is far from zero at rest and balances there; one linearisation per step
// misses the geometric stiffness of that prestress. The six Green strains (green_strain_tet.hpp)
// vanish at rest, so the element is handed on as those rows with the Neo-Hookean tangent:
//   Psi(C) = (mu/2)(tr C - 3) + (lambda/2)(J - gamma)^2,   C = F^T F,  J = det F
//   S = 2 dPsi/dC = mu I + lambda (J - gamma) J C^-1                 (dJ/dC = J C^-1 / 2)
//   DD = dS/dE = lambda (2J - gamma) J C^-1 (x) C^-1 - 2 lambda (J - gamma) J II(C^-1),
//   II(C^-1)_ijkl = (C^-1_ik C^-1_jl + C^-1_il C^-1_jk) / 2,
// which at rest is lambda_Lame 1 (x) 1 + 2 mu II, linear elasticity. In Voigt form (engineering
// shears) the rows take
//   compliance alpha = (V DD)^-1   (DD with its eigenvalues raised to at least the smallest at
//                                   rest, min(mu, 3K): where a large strain softens the tangent or
//                                   makes it indefinite, the step stays as implicit as at rest),
//   value      C = DD^-1 S,
// so the rows' force -alpha^-1 C = -V S is the Neo-Hookean stress exactly, and their stiffness
// V DD is its material tangent. On the vertices that force is -V (F S) : dF/dx, the exact
// Neo-Hookean force, inverted elements included (the rows' gradients are dE/dx = sym(F^T dF/dx)).
#include "moreau/constraints/green_strain_tet.hpp"
#include "moreau/constraints/neo_hookean_tet.hpp"

namespace moreau {

/// Element k of `family` at positions x as six Green-strain rows with the Neo-Hookean tangent.
GreenStrainTetConstraints::Rows neo_hookean_green_strain_rows(const NeoHookeanTetConstraints& family, Index k,
                                                              const Vec3* x);

}  // namespace moreau
