#include "moreau/geometry/lattice_openings.hpp"

#include <cmath>

namespace moreau {

namespace {

// Two unit vectors spanning the plane normal to n; t1 is `tangent` made orthogonal to n (or a
// world axis if tangent is zero or parallel to n).
std::pair<Vec3, Vec3> plane_axes(const Vec3& n, Vec3 tangent) {
  tangent -= tangent.dot(n) * n;
  if (tangent.norm() < 1e-9) {
    tangent = std::abs(n.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitZ();
    tangent -= tangent.dot(n) * n;
  }
  const Vec3 t1 = tangent.normalized();
  return {t1, n.cross(t1)};
}

// Symmetric lattice coordinates covering [-L/2, L/2]: floor(L / d) points, spaced d.
std::vector<Real> symmetric_coordinates(Real length, Real d) {
  const int count = std::max(1, static_cast<int>(std::floor(length / d + 1e-9)));
  std::vector<Real> out;
  for (int i = 0; i < count; ++i) out.push_back((i - 0.5 * (count - 1)) * d);
  return out;
}

}  // namespace

std::vector<Vec3> disc_opening(const Vec3& normal, Real radius, Real d) {
  const auto [t1, t2] = plane_axes(normal, Vec3::Zero());
  std::vector<Vec3> out;
  // Points whose lattice cell centre lies within the disc; an odd count per axis puts one on the axis.
  const int reach = static_cast<int>(std::floor(radius / d));
  for (int i = -reach; i <= reach; ++i)
    for (int j = -reach; j <= reach; ++j)
      if (std::hypot(i * d, j * d) <= radius + 1e-9 * d) out.push_back(i * d * t1 + j * d * t2);
  return out;
}

std::vector<Vec3> rectangle_opening(const Vec3& normal, const Vec3& tangent, Real a, Real b, Real d) {
  const auto [t1, t2] = plane_axes(normal, tangent);
  std::vector<Vec3> out;
  for (Real u : symmetric_coordinates(a, d))
    for (Real v : symmetric_coordinates(b, d)) out.push_back(u * t1 + v * t2);
  return out;
}

}  // namespace moreau
