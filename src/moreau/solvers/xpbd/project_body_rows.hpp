#pragma once
// The XPBD projection of a block of body rows (constraints/body_rows.hpp).
//
// Macklin, Mueller, Chentanez 2016 (XPBD) eq. (18) on rigid bodies (Mueller et al. 2020, sec. 3.3):
// with W_e = diag(1/m_e I, I_e^-1) the inverse mass of end e (I^-1 in the world),
//   (sum_e J_e W_e J_e^T + alpha~) dlambda = -(C + alpha~ lambda),   alpha~ = alpha / h^2,
//   dx_e = 1/m_e J_e,x^T dlambda,   q_e += 1/2 [I_e^-1 J_e,theta^T dlambda, 0] q_e (normalised).
// Damped rows take their damping by apply_xpbd_damping (body_rows.hpp).
// Bounds clamp the accumulated multiplier, lower h^2 <= lambda + dlambda <= upper h^2 (projected
// Gauss-Seidel); a block whose matrix is singular (both ends immovable) is left alone.
#include "moreau/constraints/body_rows.hpp"
#include "moreau/rigid/body_handle.hpp"

namespace moreau {

/// Projects one block between the handles of its two ends; `lambda` holds its accumulated
/// multipliers (rows.size() of them).
inline void xpbd_project_body_rows(const BodyRows& rows, const std::array<BodyHandle, 2>& ends, Real* lambda, Real h) {
  using Matrix = Eigen::Matrix<Real, Eigen::Dynamic, Eigen::Dynamic, 0, BodyRows::kMaxRows, BodyRows::kMaxRows>;
  const int n = rows.size();
  const Real h2 = h * h;
  BodyRows::Vector alpha_tilde = rows.compliance / h2, C = rows.C;
  apply_xpbd_damping(rows, h, C, alpha_tilde);
  Matrix K = alpha_tilde.asDiagonal();
  for (int e = 0; e < 2; ++e) {
    const BodyHandle& body = ends[e];
    if (body.is_world()) continue;
    const auto linear = rows.jacobian[e].leftCols<3>();
    K += body.inv_mass * linear * linear.transpose();
    if (body.rotates()) {
      const auto angular = rows.jacobian[e].rightCols<3>();
      K += angular * body.world_inv_inertia() * angular.transpose();
    }
  }
  if (K.determinant() <= 1e-300) return;
  Eigen::Map<BodyRows::Vector> accumulated(lambda, n);
  BodyRows::Vector dl = K.ldlt().solve(-(C + alpha_tilde.cwiseProduct(accumulated)));
  dl = (accumulated + dl).cwiseMax(rows.lower * h2).cwiseMin(rows.upper * h2) - accumulated;
  accumulated += dl;
  for (int e = 0; e < 2; ++e) {
    const BodyHandle& body = ends[e];
    if (body.is_world()) continue;
    *body.position += body.inv_mass * (rows.jacobian[e].leftCols<3>().transpose() * dl);
    if (body.rotates()) body.rotate_by(body.apply_inv_inertia(rows.jacobian[e].rightCols<3>().transpose() * dl));
  }
}

}  // namespace moreau
