#pragma once
// Inside test for a closed triangle surface: a ray from the point crosses the surface an odd
// number of times iff the point is inside (Jordan curve theorem). The ray direction is fixed and
// slightly oblique so that it rarely grazes an edge or vertex of axis-aligned meshes.
#include "moreau/geometry/meshes.hpp"

namespace moreau {

bool point_in_closed_mesh(const TriangleMesh& mesh, const Vec3& point);

}  // namespace moreau
