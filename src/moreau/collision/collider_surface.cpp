#include "moreau/collision/collider_surface.hpp"

#include "moreau/geometry/primitive_meshes.hpp"

#include <cmath>

namespace moreau {


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
      m = box_mesh(c.half_extents);
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
