#pragma once
// The one shape type of rigid bodies and colliders, with its mass properties. A rigid body's shape
// is stored in its body frame: the origin at the centre of mass and the axes along the principal
// axes of inertia, so its inertia tensor is diagonal there (Mueller et al. 2020, sec. 3.3:
// corrections are evaluated in the rest frame). A collider's shape is in the collider's frame
// (Collider::position and rotation; a plane collider keeps its world normal in Collider::normal).
#include <memory>
#include <string>
#include <vector>

#include "moreau/math/types.hpp"

namespace moreau {

enum class ShapeType { sphere, box, capsule, cylinder, convex_hull, plane, triangle_mesh };

/// A convex polyhedron: faces are counter-clockwise seen from outside; a face's plane is
/// {x : face_normal . x = face_offset}, the normal pointing out.
struct ConvexPolyhedron {
  std::vector<Vec3> vertices;
  std::vector<std::vector<Index>> faces;
  std::vector<Vec3> face_normals;
  std::vector<Real> face_offsets;
  std::vector<std::array<Index, 2>> edges;  // each undirected edge once
  std::vector<Vec3> edge_directions;        // unit directions, parallel edges listed once (SAT axes)

  /// Fills normals, offsets, edges and edge directions from vertices and faces.
  void finish_topology();
  /// Index of the vertex furthest along `direction`.
  Index support_vertex(const Vec3& direction) const;
};

struct MeshShape;

struct Shape {
  ShapeType type = ShapeType::sphere;
  Real radius = 0;                   // m: sphere, capsule, cylinder
  Real half_height = 0;              // m: capsule segment / cylinder, along the local y axis
  Vec3 half_extents = Vec3::Zero();  // m: box
  ConvexPolyhedron polyhedron;       // box and convex hull
  std::shared_ptr<const MeshShape> mesh;  // triangle mesh (fixed and kinematic bodies only; mesh_shape.hpp)

  bool is_polyhedron() const { return type == ShapeType::box || type == ShapeType::convex_hull; }
  /// Sphere and capsule: a core (point or segment) swept by `radius`.
  bool is_round() const { return type == ShapeType::sphere || type == ShapeType::capsule; }
  /// Radius of the smallest origin-centred sphere holding the shape (m; infinite for a plane).
  Real bounding_radius() const;
  /// Furthest point along `direction` (body frame); planes and meshes have none.
  Vec3 support(const Vec3& direction) const;
  /// Half extents of the body-frame bounding box.
  Vec3 local_half_extents() const;
};

/// Mass properties of a shape of uniform density in the frame the shape was given in.
struct MassProperties {
  Real volume = 0;                  // m^3
  Vec3 center = Vec3::Zero();       // m, centroid
  Mat3 inertia = Mat3::Zero();      // kg m^2 per kg/m^3 of density, about the centroid
};

Shape make_sphere(Real radius);
Shape make_box(const Vec3& half_extents);
Shape make_capsule(Real radius, Real half_height);
Shape make_cylinder(Real radius, Real half_height);
/// Half-space y <= 0 of its body frame (colliders only).
Shape make_plane();
/// A triangle mesh shape (its vertices in the body frame; mesh_shape.hpp).
Shape make_triangle_mesh(std::shared_ptr<const MeshShape> mesh);

/// Convex hull of `points` (computed with qhull); coplanar facets merged into polygons. Throws
/// std::invalid_argument when the points span no volume.
ConvexPolyhedron convex_hull(const std::vector<Vec3>& points);

/// Volume, centroid and inertia (per unit density) of a primitive or polyhedron in its own frame.
MassProperties mass_properties(const Shape& shape);

/// Moves a shape into its principal frame: returns the rotation R (principal -> given frame) such
/// that R^T I R is diagonal, and rewrites the polyhedron as R^T (x - centroid). Primitives are
/// already principal; for them R = identity.
Mat3 move_to_principal_frame(Shape& shape, MassProperties& props);

}  // namespace moreau
