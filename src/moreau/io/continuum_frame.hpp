#pragma once
// A continuum's frame: its particles as points.
#include "moreau/io/object_frame.hpp"

namespace moreau {

/// Point arrays: velocity (m/s), displacement from the rest point (m), radius (m, half the
/// spacing: ParaView's "Point Gaussian" by radius shows the filled volume), J = det F of the
/// elastic deformation, the accumulated plastic strain, the von Mises stress (Pa) and the
/// pressure (Pa, minus the mean Cauchy stress).
ObjectFrame continuum_frame(const Model& model, const ObjectInfo& object, const State& state);

}  // namespace moreau
