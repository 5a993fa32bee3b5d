#pragma once
// Particle emitters: grains, or the particles of a continuum (XPBI), poured through a disc or a
// rectangle during the run. (Particle fluids have their own emitter, fluids/fluid_emitter.hpp.)
//
// An emitter releases layers of particles on the lattice of its opening (spacing d: 2.04 r_max
// for grains, the granular lattice's; the particle spacing r for a continuum): layer k is due at
// t_k = start + k d / v in the opening's plane and moves along the normal n at speed v, so the
// layers arrive one spacing apart. A layer holds N particles; the mass rate is N m̄ v / d, m̄ the
// mean mass of a particle (for grains, rho 4/3 pi E[r^3] over the object's radius range: each
// grain's radius and offset are drawn when the scene is built, and the drawn masses scatter about
// m̄; for a continuum rho r^3, so the rate is N rho r^2 v). Layers are released at the start of
// each step; a layer due during the previous step is placed where it would be by now,
// x = x_k + v (t - t_k) n, with velocity v n (gravity over that part of a step is neglected).
//
// A layer waits while a particle (of any object) lies where it would appear: within r + r_max of
// the layer's plane and of the opening. The emitter then retries at every step, and all its later
// layers are due that much later, so a spout buried by the pile it made stops pouring instead of
// releasing particles into others.
//
// The nozzle (continua only): a released layer is held at the speed v until it has travelled
// `nozzle_length` past the opening, as if it were still in the pipe. A held particle moves on at
// v n whatever pushes it: it has inverse mass 0 in the substep's projections
// (moving_inverse_mass), so the continuum's constraints move the free material against it and the
// pipe carries the weight and the tension of the stream below. Without it the last layer of a
// stream would be pulled out of the opening by the stream's weight and leave a gap to the next.
// A particle that is not held inside the nozzle (short of its end by more than half a spacing:
// the stream piled up to the spout, or another object) blocks it: the held layers stand still
// and no layer is released until it has moved away, as a pipe stops when its outlet is shut,
// instead of driving its held layers into it with an unbounded force.
//
// Every particle an emitter will release exists from the start: the last particles of its object,
// layer after layer. Until released a particle is not live (State::live): it is not integrated,
// takes part in no contact and in no continuum neighbourhood, and is neither written nor probed.
#include <vector>

#include "moreau/math/types.hpp"

namespace moreau {

struct ParticleEmitter {
  Index object = -1;               // the granular or continuum object the particles belong to
  Index first = 0;                 // the first particle: layer k is [first + k N, first + (k + 1) N)
  Index per_layer = 0;             // N, lattice points of the opening
  Index layers = 0;                // layers released between start and stop
  Vec3 center = Vec3::Zero();      // m, centre of the opening
  Vec3 normal = Vec3::UnitY();     // unit flow direction
  Real spacing = 0;                // d, m
  Real speed = 1;                  // v, m/s
  Real start = 0;                  // s
  Real reach = 0;                  // m, the farthest lattice point from the centre, plus r_max
  Real max_radius = 0;             // m, r_max of the emitted particles
  Real nozzle_length = 0;          // m, a layer is held at v n this far past the opening (0: none)

  /// When layer k is due, s (before any wait for a covered opening).
  Real due(Index k) const { return start + k * spacing / speed; }
};

/// What the emitters have released.
struct ParticleEmitterState {
  std::vector<Index> released;              // per emitter: layers released
  std::vector<Index> freed;                 // per emitter: layers that have left the nozzle (all, without one)
  std::vector<Real> wait;                   // per emitter: s its layers have waited for a covered opening
  std::vector<char> unborn;                 // per particle: 1 while its emitter has not released it (empty: none)
  std::vector<char> held;                   // per particle: 1 while its layer is in the nozzle (empty: no nozzle)
  std::vector<Index> live_contact_particle; // Model::contact_particle without the unborn particles (with emitters)

  /// Whether some emitter holds layers in its nozzle.
  bool holds_layers() const {
    for (std::size_t k = 0; k < freed.size(); ++k)
      if (freed[k] < released[k]) return true;
    return false;
  }
};

struct Model;
struct State;

/// Every emitted particle unborn, at its place in the opening (a state made by make_rest_state).
void prepare_particle_emitters(const Model& model, State& state);

/// Releases every layer due by state.time whose place is free, and frees the layers that have left
/// their nozzle by then. Returns the particles released. Serial; call at the start of a step,
/// before the contact candidates are sought.
Index emit_particles(const Model& model, State& state);

}  // namespace moreau
