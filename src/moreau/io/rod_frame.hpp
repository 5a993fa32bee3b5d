#pragma once
// A rod's frame: its centreline as a polyline (one line cell per segment) with the material frame
// per segment and the strains at the centreline points.
#include "moreau/io/object_frame.hpp"

namespace moreau {

/// Point arrays: velocity (m/s), displacement from the rest point (m), curvature (1/m: the turn
/// of the tangent between neighbouring segments over the junction's length), twist (rad/m:
/// beyond the rest shape's) and stretch (the axial strain of the junction's gap); the three
/// strains are 0 at the rod's two ends. Cell arrays per segment: tangent, normal (the section's
/// first axis) and binormal.
ObjectFrame rod_frame(const Model& model, const RodModel& rod, const State& state);

}  // namespace moreau
