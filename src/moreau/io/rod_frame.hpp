#pragma once
// A rod's frame file: its centreline as a .vtp polyline (one line cell per segment) with the
// material frame per segment and the strains at the centreline points.
#include <string>

#include "moreau/model/state.hpp"

namespace moreau {

/// Point arrays: velocity (m/s), displacement from the rest point (m), curvature (1/m: the turn
/// of the tangent between neighbouring segments over the junction's length), twist (rad/m:
/// beyond the rest shape's) and stretch (the axial strain of the junction's gap); the three
/// strains are 0 at the rod's two ends. Cell arrays per segment: tangent, normal (the section's
/// first axis) and binormal.
void write_rod_frame(const std::string& path, const Model& model, const RodModel& rod, const State& state);

}  // namespace moreau
