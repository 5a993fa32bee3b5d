#include "moreau/collision/shape_surface.hpp"

#include "moreau/geometry/primitive_meshes.hpp"
#include "moreau/collision/mesh_shape.hpp"

namespace moreau {

TriangleMesh shape_surface(const Shape& s) {
  switch (s.type) {
    case ShapeType::sphere: return lat_long_sphere(s.radius, 0);
    case ShapeType::capsule: return lat_long_sphere(s.radius, s.half_height);
    case ShapeType::cylinder: return cylinder_mesh(s.radius, s.half_height);
    case ShapeType::box:
    case ShapeType::convex_hull: {
      // Fan-triangulated faces (convex polygons).
      TriangleMesh m;
      m.vertices = s.polyhedron.vertices;
      for (const auto& f : s.polyhedron.faces)
        for (size_t k = 1; k + 1 < f.size(); ++k) m.triangles.push_back({f[0], f[k], f[k + 1]});
      return m;
    }
    case ShapeType::triangle_mesh: return s.mesh->surface;
    case ShapeType::plane: break;
  }
  return {};
}

}  // namespace moreau
