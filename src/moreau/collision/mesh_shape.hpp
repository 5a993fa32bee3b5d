#pragma once
// Triangle meshes as shapes of fixed and kinematic rigid bodies (terrain, ramps, containers of any
// form). A mesh is a one-sided shell: each triangle's front is the side its vertices turn
// counter-clockwise about, and behind it lies a slab of solid `thickness` deep. Contacts:
//   - with convex bodies, each triangle near the body is that slab, a triangular prism (a convex
//     polyhedron), met by the convex narrow phase (narrow_phase.hpp); only contacts whose normal
//     lies within 60 degrees of the triangle's front normal are kept, so a body sliding over the
//     seam between two triangles is not caught by the side faces of either prism (the "internal
//     edge" problem); a body reaching a mesh's open border from the side passes it;
//   - with particles, the nearest point of the nearest triangle (point_query.hpp): in front, the
//     distance to it; behind (within the thickness), minus that distance along the front normal.
// Triangles are found through a uniform grid over their bounds in the body frame.
#include <memory>
#include <vector>

#include "moreau/geometry/meshes.hpp"
#include "moreau/math/types.hpp"

namespace moreau {

struct Shape;
struct SurfacePoint;  // point_query.hpp

struct MeshShape {
  TriangleMesh surface;                // body frame
  std::vector<Vec3> normals;           // unit front normals, per triangle
  std::vector<Shape> prisms;      // the slab behind each triangle (convex hulls)
  Real thickness = 0;                  // m
  Vec3 lower = Vec3::Zero(), upper = Vec3::Zero();  // body-frame bounds of the slabs

  // Grid over the slabs' bounds: cell (i, j, k) holds triangles [cell_begin[c], cell_begin[c + 1]).
  Real cell = 1;
  Eigen::Vector3i cells = Eigen::Vector3i::Ones();
  std::vector<Index> cell_begin, cell_triangles;

  /// Triangles whose slab bounds may overlap the body-frame box [lo, hi], sorted, each once.
  void triangles_near(const Vec3& lo, const Vec3& hi, std::vector<Index>& out) const;
  /// The grid cells [c0, c1] (inclusive, clamped to the grid) covering the body-frame box [lo, hi].
  void cell_range(const Vec3& lo, const Vec3& hi, Eigen::Vector3i& c0, Eigen::Vector3i& c1) const;
};

/// Builds the slabs and the grid. Throws std::invalid_argument for an empty mesh or one whose
/// triangles are all degenerate; degenerate triangles (zero area) are dropped.
std::shared_ptr<const MeshShape> make_mesh_shape(const TriangleMesh& mesh, Real thickness);

/// The nearest point of the mesh to body-frame point p among triangles within one grid cell of p
/// (distance, normal, point). Found nothing: distance = +inf.
SurfacePoint nearest_mesh_point(const MeshShape& mesh, const Vec3& p);

}  // namespace moreau
