#pragma once
// Triangle surfaces of colliders, for output only (the solver uses the analytic distances).
#include "moreau/collision/collider.hpp"
#include "moreau/geometry/meshes.hpp"

namespace moreau {

/// The collider's surface at `time`. Planes are drawn as a square of half-size `plane_half_size`
/// around their reference point.
TriangleMesh collider_surface(const Collider& c, Real time, Real plane_half_size);

}  // namespace moreau
