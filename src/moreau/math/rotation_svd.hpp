#pragma once
// The singular value decomposition of a 3 x 3 matrix with rotations on both sides:
// F = U diag(sigma) V^T with det U = det V = +1, sigma_1 >= sigma_2 >= |sigma_3|, and sigma_3 < 0
// when det F < 0 (an inverted element keeps its inversion in its smallest stretch instead of in a
// reflection). The form that isotropic hyperelasticity and plasticity work in (Irving, Teran,
// Fedkiw 2004, "Invertible finite elements for robust simulation of large deformation").
#include <Eigen/SVD>

#include "moreau/math/types.hpp"

namespace moreau {

struct RotationSvd {
  Mat3 U, V;
  Vec3 sigma;

  Mat3 compose() const { return U * sigma.asDiagonal() * V.transpose(); }
};

inline RotationSvd rotation_svd(const Mat3& F) {
  const Eigen::JacobiSVD<Mat3> svd(F, Eigen::ComputeFullU | Eigen::ComputeFullV);
  RotationSvd r{svd.matrixU(), svd.matrixV(), svd.singularValues()};
  // A reflection on either side moves to the smallest singular value's sign.
  if (r.U.determinant() < 0) {
    r.U.col(2) = -r.U.col(2);
    r.sigma[2] = -r.sigma[2];
  }
  if (r.V.determinant() < 0) {
    r.V.col(2) = -r.V.col(2);
    r.sigma[2] = -r.sigma[2];
  }
  return r;
}

}  // namespace moreau
