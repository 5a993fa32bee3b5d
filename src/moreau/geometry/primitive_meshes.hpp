#pragma once
// Triangle meshes of primitive shapes for output (ParaView/Blender), centred at the origin.
#include "moreau/geometry/meshes.hpp"

namespace moreau {

/// Latitude-longitude sphere of `radius`; with lift > 0 the upper half moves up by lift and the
/// lower half down, which makes a capsule whose segment runs along y.
TriangleMesh lat_long_sphere(Real radius, Real lift, int rings = 12, int segments = 24);

/// Box with half extents h.
TriangleMesh box_mesh(const Vec3& h);

/// Closed cylinder of `radius` along y from -half_height to +half_height.
TriangleMesh cylinder_mesh(Real radius, Real half_height, int segments = 32);

}  // namespace moreau
