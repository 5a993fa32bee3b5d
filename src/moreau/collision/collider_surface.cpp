#include "moreau/collision/collider_surface.hpp"

#include "moreau/geometry/primitive_meshes.hpp"

#include <cmath>

namespace moreau {


TriangleMesh collider_surface(const Collider& c, Real time, Real plane_half_size) {
  const Vec3 center = c.position_at(time);
  TriangleMesh m;
  Mat3 R = c.rotation;
  switch (c.shape.type) {
    case ShapeType::plane: {
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
    case ShapeType::box:
      m = box_mesh(c.shape.half_extents);
      break;
    case ShapeType::sphere:
      m = lat_long_sphere(c.shape.radius, 0);
      break;
    case ShapeType::capsule:
      m = lat_long_sphere(c.shape.radius, c.shape.half_height);
      break;
    default: unsupported_collider_shape(c.shape.type);
  }
  for (auto& v : m.vertices) v = center + R * v;
  return m;
}

}  // namespace moreau
