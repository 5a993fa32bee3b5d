#pragma once
// Total-Lagrangian hyperelastic element: internal force, tangent and stored energy of one cell
// from its nodal displacements, with the reference-configuration shape gradients precomputed.
//
//   F = I + sum_a u_a (x) G_a,  G_a = dN_a/dX,   C = F^T F,   S = S(C),  CC = CC(C)
//   dE = sym(F^T grad du)  ->  dE_voigt = sum_a B_a du_a  with, for a displacement component k,
//     B_a[11] = F_k1 G_a1, B_a[22] = F_k2 G_a2, B_a[33] = F_k3 G_a3,
//     B_a[12] = F_k1 G_a2 + F_k2 G_a1, B_a[23] = F_k2 G_a3 + F_k3 G_a2, B_a[13] = F_k1 G_a3 + F_k3 G_a1
//   f_a  = sum_qp w B_a^T S                                          (internal force)
//   K_ab = sum_qp w (B_a^T CC B_b + (G_a . S G_b) I)                  (material + geometric)
// (Bonet & Wood, Nonlinear Continuum Mechanics for Finite Element Analysis, ch. 7; Belytschko,
// Liu & Moran, Nonlinear Finite Elements, sec. 4.9.) In 2D (plane strain) the third components of
// u and G are zero and F_33 = 1; w is then per unit thickness.
#include <Eigen/Dense>

#include "moreau/fem/core/elements.hpp"
#include "moreau/materials/hyperelastic.hpp"

namespace moreau {

constexpr int kMaxElementDofs = 3 * kMaxElementNodes;
using ElementVector = Eigen::Matrix<Real, Eigen::Dynamic, 1, 0, kMaxElementDofs, 1>;
using ElementMatrix = Eigen::Matrix<Real, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxElementDofs, kMaxElementDofs>;

/// One cell's quadrature data: per point the weight w = w_gauss det(dX/dxi) and the gradients G_a.
struct CellQuadrature {
  int points = 0, nodes = 0;
  const Real* weight = nullptr;  // [points]
  const Vec3* gradient = nullptr;  // [points][nodes]
};

/// What to compute for a cell.
struct ElementOutput {
  Real energy = 0;       // J (2D: J/m)
  ElementVector force;   // internal force, dim * nodes, node-major
  ElementMatrix tangent; // when asked for
  bool valid = true;     // false if a point is inverted (det F <= 0) or W is undefined there
};

/// How a cell treats its volume change: at every quadrature point (the displacement element), or
/// through its mean dilatation (mean_dilatation.hpp: locking-free for nearly incompressible
/// Neo-Hookean solids, quad4/hex8).
enum class VolumeTreatment { pointwise, mean_dilatation };

/// Internal force, energy and (if `with_tangent`) tangent of a cell; `u` holds the nodal
/// displacements (dim per node, node-major); `dim` is 2 or 3.
void solid_element(const HyperelasticMaterial& material, VolumeTreatment volume, const CellQuadrature& q, int dim,
                   const Real* u, bool with_tangent, ElementOutput& out);

/// How the internal force of a time step is evaluated between u_n and u_n+1 (midpoint rule, or Gonzalez's discrete gradient).
enum class StepRule {
  midpoint,         // f = f_int(u_n+1/2): the implicit midpoint rule
  energy_momentum,  // f = sum_qp w B(F_n+1/2)^T S_algo, Gonzalez's discrete gradient in E
};

/// Algorithmic internal force of a step, the stored energy at n+1 and (if asked) an approximate
/// tangent d f / d u_n+1. Gonzalez (2000), written in E = (C - I)/2:
///   E_avg = (E_n + E_n+1)/2,  dE = E_n+1 - E_n,
///   S_algo = S(E_avg) + (W(E_n+1) - W(E_n) - S(E_avg) : dE) / (dE : dE) dE
/// so that S_algo : dE = W(E_n+1) - W(E_n) exactly; with E_n+1 - E_n = sym(F_n+1/2^T grad(du))
/// (E is quadratic in u) the force does work W_n+1 - W_n: energy is conserved, and S_algo is
/// symmetric, so angular momentum is too. The correction is skipped when |dE| < 1e-8 (its
/// numerator is then round-off; what it would add is O(|dE|^3)). Tangent: midpoint
/// (1/2)(B_m^T CC B_m + geometric(S)), exact and symmetric; energy_momentum
/// (1/2)(B_m^T (CC(E_avg) + 2 dS_corr/dE_n+1) B_n+1 + geometric(S_algo)), exact and not symmetric
/// (dE_avg/du_n+1 = B_n+1 / 2). (The symmetric B_m^T CC B_m in its place is off by
/// O(|H_n+1 - H_n|) times the stiffness: Newton then diverged on a stiff spinning body; without the
/// correction's derivative it converged only linearly, 8 iterations per step on the flying L.)
void solid_element_step(const HyperelasticMaterial& material, VolumeTreatment volume, const CellQuadrature& q,
                        int dim, const Real* u_n, const Real* u_next, StepRule rule, bool with_tangent,
                        ElementOutput& out);

/// The displacement gradient H = F - I at one quadrature point (dim per node displacements),
/// summed directly so that small strains keep their digits.
Mat3 displacement_gradient(const Vec3* gradient, int nodes, int dim, const Real* u);

}  // namespace moreau
