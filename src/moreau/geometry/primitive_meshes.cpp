#include "moreau/geometry/primitive_meshes.hpp"

#include <cmath>

namespace moreau {

TriangleMesh lat_long_sphere(Real radius, Real lift, int rings, int segments) {
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

TriangleMesh box_mesh(const Vec3& h) {
  TriangleMesh m;
  for (int k = 0; k < 8; ++k) m.vertices.emplace_back((k & 1 ? 1 : -1) * h.x(), (k & 2 ? 1 : -1) * h.y(), (k & 4 ? 1 : -1) * h.z());
  const int faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& f : faces) {
    m.triangles.push_back({f[0], f[1], f[2]});
    m.triangles.push_back({f[0], f[2], f[3]});
  }
  return m;
}

TriangleMesh cylinder_mesh(Real radius, Real half_height, int segments) {
  TriangleMesh m;
  for (int j = 0; j < segments; ++j) {
    const Real phi = 2 * kPi * j / segments;
    const Real x = radius * std::cos(phi), z = radius * std::sin(phi);
    m.vertices.emplace_back(x, -half_height, z);
    m.vertices.emplace_back(x, half_height, z);
  }
  const Index bottom = static_cast<Index>(m.vertices.size());
  m.vertices.emplace_back(0, -half_height, 0);
  m.vertices.emplace_back(0, half_height, 0);
  for (int j = 0; j < segments; ++j) {
    const Index a = 2 * j, b = 2 * ((j + 1) % segments);
    m.triangles.push_back({a, a + 1, b});
    m.triangles.push_back({b, a + 1, b + 1});
    m.triangles.push_back({bottom, a, b});
    m.triangles.push_back({bottom + 1, b + 1, a + 1});
  }
  return m;
}

}  // namespace moreau
