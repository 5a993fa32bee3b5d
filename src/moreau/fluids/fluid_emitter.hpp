#pragma once
// Fluid emitters: inflow through a disc or a rectangle, for pouring.
//
// An emitter releases layers of particles on the 2r lattice of its opening: layer k is born at
// t_k = start + k 2r / v in the opening's plane and moves along the normal n at speed v, so the
// layers arrive one lattice spacing apart and the stream has the rest density. The volume rate is
// exactly N (2r)^2 v for an opening of N lattice points (a requested flow rate Q sets v = Q / (N (2r)^2)).
// Layers are released at the start of each step; a layer born during the previous step is placed
// where it would be by now, x = c + v (t - t_k) n, with velocity v n. Emission ends at `stop`
// (by default the scene file's duration): the fluid arrays are sized for every layer up to then.
// The nozzle: a layer is held at the speed v until it has travelled `nozzle_length` past the
// opening (by default 4r = h, two layers: a full kernel of held fluid behind the first free
// layer), as if it were still in the pipe. Held particles have inverse mass 0: the density and
// viscosity solves move the free fluid against them and leave them on their course, so the pipe
// carries the weight and the tension of the stream below (a viscous thread hangs from it instead
// of falling freely, layer by layer). FluidState::release_time marks them.
// The stream is assumed to flow freely: an opening blocked by fluid that has not moved away
// would receive overlapping particles (the density constraint then pushes them apart violently).
#include <vector>

#include "moreau/geometry/lattice_openings.hpp"
#include "moreau/math/types.hpp"

namespace moreau {

struct FluidEmitter {
  Index phase = 0;                 // the fluid phase (object) the particles join
  Vec3 center = Vec3::Zero();      // m, centre of the opening
  Vec3 normal = Vec3::UnitY();     // unit flow direction
  std::vector<Vec3> opening;       // m, lattice points of the opening relative to `center`
  Real speed = 1;                  // v, m/s
  Real start = 0, stop = 0;        // s
  Index layers = 0;                // layers released between start and stop
  Real nozzle_length = 0;          // m, the stream is held at `speed` this far past the opening

  Index capacity() const { return layers * static_cast<Index>(opening.size()); }
  /// Birth time of layer k, s.
  Real birth(Index k, Real spacing) const { return start + k * spacing / speed; }
};

struct Model;
struct FluidState;

/// Releases every layer born by `time`, and frees the particles whose layer has left its nozzle by
/// then. Returns the number of particles added. Serial; call outside parallel regions (marks the
/// neighbour lists stale when it adds particles).
Index emit_fluid(const Model& model, FluidState& fluid, Real time);

}  // namespace moreau
