#pragma once
// The lattice points of an emitter's opening (fluids and grains): a disc or a rectangle in the
// plane through the origin normal to the flow direction.
#include <vector>

#include "moreau/math/types.hpp"

namespace moreau {

/// Lattice points (spacing d) of an opening in the plane through the origin normal to n: a disc
/// of radius R (points (i d, j d) with |.| <= R, one on the axis), or a rectangle a x b along t1
/// (`tangent` made normal to n) and n x t1 (floor(a / d) x floor(b / d) points, centred).
std::vector<Vec3> disc_opening(const Vec3& normal, Real radius, Real d);
std::vector<Vec3> rectangle_opening(const Vec3& normal, const Vec3& tangent, Real a, Real b, Real d);

}  // namespace moreau
