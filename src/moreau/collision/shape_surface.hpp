#pragma once
// The surface of a rigid shape as triangles in its body frame (for output).
#include "moreau/geometry/meshes.hpp"
#include "moreau/collision/shape.hpp"

namespace moreau {

TriangleMesh shape_surface(const Shape& shape);

}  // namespace moreau
