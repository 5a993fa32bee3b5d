#include "moreau/geometry/point_in_mesh.hpp"

#include <cmath>

namespace moreau {

bool point_in_closed_mesh(const TriangleMesh& mesh, const Vec3& point) {
  const Vec3 dir = Vec3(1, 0.000123456789, 0.000234567891).normalized();
  int crossings = 0;
  for (const auto& t : mesh.triangles) {
    // Moeller-Trumbore ray/triangle intersection, counting hits at ray parameter s > 0.
    const Vec3& a = mesh.vertices[t[0]];
    const Vec3 e1 = mesh.vertices[t[1]] - a, e2 = mesh.vertices[t[2]] - a;
    const Vec3 p = dir.cross(e2);
    const Real det = e1.dot(p);
    if (std::abs(det) < 1e-300) continue;
    const Real inv = 1 / det;
    const Vec3 s = point - a;
    const Real u = s.dot(p) * inv;
    if (u < 0 || u > 1) continue;
    const Vec3 q = s.cross(e1);
    const Real v = dir.dot(q) * inv;
    if (v < 0 || u + v > 1) continue;
    if (e2.dot(q) * inv > 0) ++crossings;
  }
  return crossings % 2 == 1;
}

}  // namespace moreau
