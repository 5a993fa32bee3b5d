#pragma once
// Where a rod is now: its centreline points, their velocities and its twist, read from the
// segments' poses (rod_model.hpp).
#include <vector>

#include "moreau/constraints/joints/joint.hpp"
#include "moreau/model/state.hpp"

namespace moreau {

/// Centreline point k now: an end of a segment; a junction's point is the midpoint of the two
/// segments' ends there (they part by the junction's stretch and shear).
Vec3 rod_point(const RodModel& rod, const RigidBodyState& bodies, Index k);
/// Velocity of centreline point k (the same averaging).
Vec3 rod_point_velocity(const RodModel& rod, const RigidBodyState& bodies, Index k);
/// The twist at one junction now (rad): the rotation of its second frame relative to its first
/// about the first's x axis (the rod's tangent), in (-pi, pi].
Real junction_twist(const Joint& junction, const State& state);
/// The twist of the rod now (rad): the turn of its last segment about the tangent relative to its
/// start, beyond the rest shape's: the sum over its junctions, and over a clamped start's (the
/// first segment's turn against the world).
Real rod_twist(const RodModel& rod, const std::vector<Joint>& joints, const State& state);
/// The elastic energy of the rod's junctions and held ends now (J): the sum of C^2 / (2 alpha)
/// over their rows.
Real rod_elastic_energy(const RodModel& rod, const std::vector<Joint>& joints, const State& state);

}  // namespace moreau
