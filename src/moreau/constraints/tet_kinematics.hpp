#pragma once
// Deformation gradient of a linear tetrahedron and the chain rule from dC/dF to vertex gradients.
//   D_m = [X1-X0, X2-X0, X3-X0],  D_s = [x1-x0, x2-x0, x3-x0],  F = D_s D_m^-1
//   [grad_x1 C, grad_x2 C, grad_x3 C] = (dC/dF) D_m^-T,   grad_x0 C = -(sum of the others)
#include <array>

#include "moreau/math/types.hpp"

namespace moreau {

/// The edge matrix [x1 - x0, x2 - x0, x3 - x0] (D_s of the current, D_m of the rest positions).
inline Mat3 tet_edge_matrix(const Vec3& x0, const Vec3& x1, const Vec3& x2, const Vec3& x3) {
  Mat3 D;
  D.col(0) = x1 - x0;
  D.col(1) = x2 - x0;
  D.col(2) = x3 - x0;
  return D;
}
inline Mat3 tet_edge_matrix(const std::array<Vec3, 4>& x) { return tet_edge_matrix(x[0], x[1], x[2], x[3]); }

inline Mat3 tet_deformation_gradient(const Vec3& x0, const Vec3& x1, const Vec3& x2, const Vec3& x3,
                                     const Mat3& rest_inverse) {
  return tet_edge_matrix(x0, x1, x2, x3) * rest_inverse;
}

inline std::array<Vec3, 4> tet_vertex_gradients(const Mat3& dC_dF, const Mat3& rest_inverse) {
  const Mat3 G = dC_dF * rest_inverse.transpose();
  return {-(G.col(0) + G.col(1) + G.col(2)), G.col(0), G.col(1), G.col(2)};
}

/// Cofactor matrix of F = d(det F)/dF, columns f2 x f3, f3 x f1, f1 x f2.
inline Mat3 cofactor(const Mat3& F) {
  Mat3 cof;
  cof.col(0) = F.col(1).cross(F.col(2));
  cof.col(1) = F.col(2).cross(F.col(0));
  cof.col(2) = F.col(0).cross(F.col(1));
  return cof;
}

}  // namespace moreau
