#pragma once
// The singular value decomposition of a 3 x 3 matrix with rotations on both sides:
// F = U diag(sigma) V^T with det U = det V = +1, sigma_1 >= sigma_2 >= |sigma_3|, and sigma_3 < 0
// when det F < 0 (an inverted element keeps its inversion in its smallest stretch instead of in a
// reflection). The form that isotropic hyperelasticity and plasticity work in (Irving, Teran,
// Fedkiw 2004, "Invertible finite elements for robust simulation of large deformation").
#include <Eigen/Eigenvalues>
#include <Eigen/Jacobi>

#include <algorithm>
#include <array>
#include <utility>

#include "moreau/math/types.hpp"

namespace moreau {

struct RotationSvd {
  Mat3 U, V;
  Vec3 sigma;

  Mat3 compose() const { return U * sigma.asDiagonal() * V.transpose(); }
};

// Without Eigen's iterative JacobiSVD, which the continua would call for every particle in every
// iteration: V and sigma^2 are the eigenvectors and eigenvalues of the symmetric F^T F, from
// Eigen's direct 3 x 3 solver (Cardano's roots and cross products), made orthonormal and polished
// by one cyclic Jacobi sweep, because a double root of the characteristic cubic comes out only to
// sqrt(machine epsilon) and so do its eigenvectors; the sweep turns that error into its square. Then, largest
// first and V a rotation, u_1 = F v_1 / |F v_1|, u_2 the unit part of F v_2 normal to u_1,
// u_3 = u_1 x u_2, and sigma_i = u_i . F v_i, so that sigma_3 carries the sign of det F. Where F v_2
// vanishes (F of rank one), u_2 is any unit vector normal to u_1. tests/continuum/
// test_hencky_elasticity.cpp compares it with JacobiSVD; in a sand column's profile it took
// less than half JacobiSVD's share of the time.
inline RotationSvd rotation_svd(const Mat3& F) {
  const Mat3 A = F.transpose() * F;
  Eigen::SelfAdjointEigenSolver<Mat3> eigen;
  eigen.computeDirect(A);
  // The eigenvectors of a double root are orthogonal only to sqrt(epsilon): make them orthonormal,
  // then diagonalise what is left.
  Mat3 V;
  V.col(0) = eigen.eigenvectors().col(0).normalized();
  V.col(1) = (eigen.eigenvectors().col(1) - V.col(0).dot(eigen.eigenvectors().col(1)) * V.col(0)).normalized();
  V.col(2) = V.col(0).cross(V.col(1));
  Mat3 D = V.transpose() * A * V;
  for (const auto& [p, q] : {std::pair{0, 1}, std::pair{0, 2}, std::pair{1, 2}}) {
    Eigen::JacobiRotation<Real> rotation;
    if (!rotation.makeJacobi(D, p, q)) continue;  // already diagonal in (p, q)
    D.applyOnTheLeft(p, q, rotation.adjoint());
    D.applyOnTheRight(p, q, rotation);
    V.applyOnTheRight(p, q, rotation);
  }
  // Largest eigenvalue first.
  std::array<int, 3> order{0, 1, 2};
  std::sort(order.begin(), order.end(), [&](int a, int b) { return D(a, a) > D(b, b); });
  RotationSvd r;
  r.V.col(0) = V.col(order[0]);
  r.V.col(1) = V.col(order[1]);
  r.V.col(2) = r.V.col(0).cross(r.V.col(1));
  const Vec3 Fv0 = F * r.V.col(0), Fv1 = F * r.V.col(1);
  const Real norm0 = Fv0.norm();
  if (!(norm0 > 0)) return {Mat3::Identity(), Mat3::Identity(), Vec3::Zero()};  // F = 0
  r.U.col(0) = Fv0 / norm0;
  Vec3 u1 = Fv1 - r.U.col(0).dot(Fv1) * r.U.col(0);
  const Real norm1 = u1.norm();
  u1 = norm1 > 1e-14 * norm0 ? Vec3(u1 / norm1) : r.U.col(0).unitOrthogonal();  // rank one
  r.U.col(1) = u1;
  r.U.col(2) = r.U.col(0).cross(u1);
  r.sigma = Vec3(norm0, u1.dot(Fv1), r.U.col(2).dot(F * r.V.col(2)));
  return r;
}

}  // namespace moreau
