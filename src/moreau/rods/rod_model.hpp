#pragma once
// A Cosserat rod of the constraint engine: a chain of rigid segments (capsules along their local
// y axis, the rod's tangent) joined at junctions by rod joints (constraints/joints/rod_joint.cpp;
// Deul et al. 2018). Segment k runs from centreline point k to point k + 1; its body frame is
// the rod's material frame: y the tangent, x and z the section's axes.
#include <vector>

#include "moreau/math/types.hpp"

namespace moreau {

struct RodModel {
  Index object = -1;
  Index first_body = -1, segments = 0;   // segment k is rigid body first_body + k
  Index first_joint = -1;                // junction k (between segments k and k + 1) is joint first_joint + k
  Index joint_count = 0;                 // the junctions, then the ends held to the world
  Index start_joint = -1, end_joint = -1;  // the joints holding the start and the end (-1: free)
  std::vector<Real> segment_length;      // m, per segment
  std::vector<Vec3> rest_points;         // m, the centreline at rest (segments + 1 points)

  Index points() const { return segments + 1; }
  /// Whether centreline point k of the rod is the start of segment k (the last point ends the last segment).
  Index segment_of_point(Index k) const { return k < segments ? k : segments - 1; }
  /// The centreline point nearest `p` at rest (the lowest index on a tie).
  Index nearest_rest_point(const Vec3& p) const {
    Index best = 0;
    for (Index k = 1; k < points(); ++k)
      if ((rest_points[k] - p).squaredNorm() < (rest_points[best] - p).squaredNorm()) best = k;
    return best;
  }
  /// Centreline point k's offset from its segment's centre in the segment's frame.
  Vec3 point_in_segment(Index k) const {
    const Real half = segment_length[segment_of_point(k)] / 2;
    return Vec3(0, k < segments ? -half : half, 0);
  }
};

}  // namespace moreau
