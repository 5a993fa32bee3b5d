#pragma once
// Scalar and small-vector types used throughout moreau. Everything is double precision: XPBD with
// small substeps needs it (Macklin et al. 2019, "Small Steps", note on precision).
#include <Eigen/Dense>
#include <array>
#include <cstdint>
#include <limits>

namespace moreau {

using Real = double;
using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;
using Mat2 = Eigen::Matrix2d;
using Mat3 = Eigen::Matrix3d;
using VectorX = Eigen::VectorXd;
using Mat32 = Eigen::Matrix<double, 3, 2>;
using Quat = Eigen::Quaterniond;  // Hamilton convention, (w, x, y, z)
using Index = std::int32_t;

inline constexpr Real kPi = 3.14159265358979323846;
inline constexpr Real kInfinity = std::numeric_limits<Real>::infinity();

/// [r]x, the matrix with [r]x v = r x v.
inline Mat3 cross_matrix(const Vec3& r) {
  Mat3 m;
  m << 0, -r.z(), r.y(), r.z(), 0, -r.x(), -r.y(), r.x(), 0;
  return m;
}

}  // namespace moreau
