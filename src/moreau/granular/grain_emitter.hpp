#pragma once
// Grain emitters: grains poured through a disc or a rectangle during the run.
//
// An emitter releases layers of grains on the lattice of its opening (spacing d = 2.04 r_max, the
// granular lattice's): layer k is due at t_k = start + k d / v in the opening's plane and moves
// along the normal n at speed v, so the layers arrive one spacing apart. A layer holds N grains;
// the mass rate is N m̄ v / d, m̄ the expected mass of a grain of the object's radius range,
// rho 4/3 pi E[r^3] (each grain's radius and offset are drawn when the scene is built, and the
// drawn masses scatter about m̄). Layers are released at the start of each step; a
// layer due during the previous step is placed where it would be by now, x = x_k + v (t - t_k) n,
// with velocity v n (gravity over that part of a step is neglected).
//
// A layer waits while a grain (of any object) lies where it would appear: within r + r_max of the
// layer's plane and of the opening. The emitter then retries at every step, and all its later
// layers are due that much later, so a spout buried by the pile it made stops pouring instead of
// releasing grains into others.
//
// Every grain an emitter will release exists from the start: the last particles of its object,
// layer after layer. Until released a grain is not live (State::live): it is not integrated,
// takes part in no contact, and is neither written nor probed.
#include <vector>

#include "moreau/math/types.hpp"

namespace moreau {

struct GrainEmitter {
  Index object = -1;               // the granular object the grains belong to
  Index first = 0;                 // the first grain: layer k is [first + k N, first + (k + 1) N)
  Index per_layer = 0;             // N, lattice points of the opening
  Index layers = 0;                // layers released between start and stop
  Vec3 center = Vec3::Zero();      // m, centre of the opening
  Vec3 normal = Vec3::UnitY();     // unit flow direction
  Real spacing = 0;                // d, m
  Real speed = 1;                  // v, m/s
  Real start = 0;                  // s
  Real reach = 0;                  // m, the farthest lattice point from the centre, plus r_max
  Real max_radius = 0;             // m, r_max of the emitted grains

  /// When layer k is due, s (before any wait for a covered opening).
  Real due(Index k) const { return start + k * spacing / speed; }
};

/// What the emitters have released.
struct GrainEmitterState {
  std::vector<Index> released;              // per emitter: layers released
  std::vector<Real> wait;                   // per emitter: s its layers have waited for a covered opening
  std::vector<char> unborn;                 // per particle: 1 while its emitter has not released it (empty: none)
  std::vector<Index> live_contact_particle; // Model::contact_particle without the unborn grains (with emitters)
};

struct Model;
struct State;

/// Every emitted grain unborn, at its place in the opening (a state made by make_rest_state).
void prepare_grain_emitters(const Model& model, State& state);

/// Releases every layer due by state.time whose place is free. Returns the grains released.
/// Serial; call at the start of a step, before the contact candidates are sought.
Index emit_grains(const Model& model, State& state);

}  // namespace moreau
