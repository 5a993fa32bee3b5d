#include "moreau/collision/collider_surface.hpp"

#include <cmath>

namespace moreau {

namespace {

// Latitude-longitude sphere; the upper hemisphere is shifted by +lift along y and the lower one
// by -lift, which turns it into a capsule when lift > 0.
TriangleMesh lat_long_sphere(Real radius, Real lift, int rings = 12, int segments = 24) {
  TriangleMesh m;
  for (int i = 0; i <= rings; ++i) {
    const Real theta = kPi * i / rings;
    for (int j = 0; j < segments; ++j) {
      const Real phi = 2 * kPi * j / segments;
      const Real y = radius * std::cos(theta);
      m.vertices.emplace_back(radius * std::sin(theta) * std::cos(phi), y + (i <= rings / 2 ? lift : -lift),
                              radius * std::sin(theta) * std::sin(phi));
    }
  }
  for (int i = 0; i < rings; ++i)
    for (int j = 0; j < segments; ++j) {
      const Index a = i * segments + j, b = i * segments + (j + 1) % segments;
      const Index c = a + segments, d = b + segments;
      m.triangles.push_back({a, b, c});
      m.triangles.push_back({b, d, c});
    }
  return m;
}

TriangleMesh unit_box(const Vec3& h) {
  TriangleMesh m;
  for (int k = 0; k < 8; ++k) m.vertices.emplace_back((k & 1 ? 1 : -1) * h.x(), (k & 2 ? 1 : -1) * h.y(), (k & 4 ? 1 : -1) * h.z());
  const int faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& f : faces) {
    m.triangles.push_back({f[0], f[1], f[2]});
    m.triangles.push_back({f[0], f[2], f[3]});
  }
  return m;
}

}  // namespace

TriangleMesh collider_surface(const Collider& c, Real time, Real plane_half_size) {
  const Vec3 center = c.position_at(time);
  TriangleMesh m;
  Mat3 R = c.rotation;
  switch (c.shape) {
    case ColliderShape::plane: {
      const Vec3 u = (std::abs(c.normal.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY()).cross(c.normal).normalized();
      const Vec3 v = c.normal.cross(u);
      R.col(0) = u;
      R.col(1) = c.normal;
      R.col(2) = v;
      const Real s = plane_half_size;
      m.vertices = {Vec3(-s, 0, -s), Vec3(s, 0, -s), Vec3(s, 0, s), Vec3(-s, 0, s)};
      m.triangles = {{0, 2, 1}, {0, 3, 2}};
      break;
    }
    case ColliderShape::box:
      m = unit_box(c.half_extents);
      break;
    case ColliderShape::sphere:
      m = lat_long_sphere(c.radius, 0);
      break;
    case ColliderShape::capsule:
      m = lat_long_sphere(c.radius, c.half_height);
      break;
  }
  for (auto& v : m.vertices) v = center + R * v;
  return m;
}

}  // namespace moreau
