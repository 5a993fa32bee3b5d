#pragma once
// The nearest surface point of a rigid shape to a point, in the shape's body frame: signed
// distance (negative inside), the outward unit normal there and the surface point itself. Used by
// particle-body contacts (particle_body_contacts.hpp) and by the sphere-polyhedron narrow phase.
//
//   sphere    d = |p| - R
//   capsule   d = |p - c| - R, c the nearest point of the core segment (local y, |y| <= H)
//   box       outside: the distance to the clamped point; inside: the nearest face
//   cylinder  radial distance rho - R and axial |y| - H; outside both, the rim
//   polyhedron inside: the nearest face plane; outside: the nearest face (its polygon holds the
//             projection) or edge
//   plane     the half-space y <= 0: d = y
//   mesh      the nearest triangle within one grid cell (mesh_shape.hpp); none: d = +infinity
#include "moreau/collision/shape.hpp"

namespace moreau {

struct SurfacePoint {
  Real distance = 0;               // m, negative inside
  Vec3 normal = Vec3::UnitY();     // body frame, outward
  Vec3 point = Vec3::Zero();       // body frame, on the surface
};

SurfacePoint nearest_surface_point(const Shape& shape, const Vec3& p);

/// The same for a convex polyhedron alone.
SurfacePoint nearest_polyhedron_point(const ConvexPolyhedron& poly, const Vec3& p);

}  // namespace moreau
