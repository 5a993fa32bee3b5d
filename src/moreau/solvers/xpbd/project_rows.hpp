#pragma once
// The XPBD projection of any family's rows (constraint_rows.hpp).
//
// Macklin, Mueller, Chentanez 2016 (XPBD), eq. (18) with the damping of eq. (26), for a block of
// R rows with gradient blocks G_i (R x 3) over particles i of inverse mass w_i:
//   [(1 + gamma) sum_i w_i G_i G_i^T + alpha~] dlambda = -(C + alpha~ lambda + gamma sum_i G_i (x_i - x_start_i))
//   x_i += w_i G_i^T dlambda,   lambda += dlambda,
// with alpha~ = alpha / h^2 and gamma = tau / h (substep_context.hpp). Bounds clamp the
// accumulated multiplier, lower <= lambda + dlambda <= upper, as projected Gauss-Seidel does for
// unilateral and friction rows; bilateral rows have infinite bounds and are not changed by it.
#include "moreau/constraints/constraint_batches.hpp"
#include "moreau/constraints/constraint_family.hpp"
#include "moreau/solvers/xpbd/substep_context.hpp"

namespace moreau {

/// Projects constraint k of `family` once; lambda is its accumulated multiplier block.
template <ParticleConstraintFamily Family>
void xpbd_project_rows(const Family& family, Index k, typename Family::Multiplier& lambda, const SubstepContext& s) {
  using Rows = typename Family::Rows;
  constexpr int R = Rows::kRows, P = Rows::kParticles;
  using Vector = typename Rows::Vector;
  using Matrix = Eigen::Matrix<Real, R, R>;
  const Rows rows = family.rows(k, s.x);
  const Real gamma = rows.damping_time * s.inv_h;
  Matrix JWJt = Matrix::Zero();
  Vector J_dx = Vector::Zero();
  for (int i = 0; i < P; ++i) {
    const Index p = rows.particle[i];
    JWJt += s.inv_mass[p] * rows.gradient[i] * rows.gradient[i].transpose();
    J_dx += rows.gradient[i] * (s.x[p] - s.x_start[p]);
  }
  const Matrix alpha_tilde = rows.compliance * s.inv_h2;
  const Matrix A = (1 + gamma) * JWJt + alpha_tilde;
  auto lambda_rows = multiplier_rows<Family>(lambda);
  const Vector rhs = -(rows.C + alpha_tilde * lambda_rows + gamma * J_dx);
  Vector dl = A.ldlt().solve(rhs);
  if (!dl.allFinite() || !(A.diagonal().array() > 0).all()) return;  // every particle fixed, or degenerate rows
  dl = (lambda_rows + dl).cwiseMax(rows.lower).cwiseMin(rows.upper) - lambda_rows;
  lambda_rows += dl;
  for (int i = 0; i < P; ++i) {
    const Index p = rows.particle[i];
    s.x[p] += s.inv_mass[p] * (rows.gradient[i].transpose() * dl);
  }
}

/// One Gauss-Seidel sweep of the generic projection over every constraint of `family`, by colour.
template <ParticleConstraintFamily Family>
void xpbd_project(const Family& family, typename Family::Multiplier* lambda, const SubstepContext& s) {
  for_each_by_color(family.batches, [&](Index k) { xpbd_project_rows(family, k, lambda[k], s); });
}

}  // namespace moreau
