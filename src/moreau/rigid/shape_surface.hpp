#pragma once
// The surface of a rigid shape as triangles in its body frame (for output).
#include "moreau/geometry/meshes.hpp"
#include "moreau/rigid/rigid_shape.hpp"

namespace moreau {

TriangleMesh shape_surface(const RigidShape& shape);

}  // namespace moreau
