#pragma once
// Sleeping grains: a settled pile costs almost nothing (settings.sleep).
//
// A grain (a particle of a granular object) is still while it stays within settings.sleep.speed
// times settings.sleep.time of where its stillness began: over the sleep time its mean speed is
// below the sleep speed, however its velocity jitters from step to step (a resting pile solved
// with few iterations keeps velocities of the order of g h in its upper grains). Grains joined by contact candidates (and the spheres of a clump) form an island; an island whose every
// grain has been still for settings.sleep.time falls asleep: its velocities become zero, it is
// no longer integrated, and no contacts are sought between two sleeping grains, nor between a
// sleeping grain and a fixed collider or body. An island stays awake while it touches what does
// not sleep: a particle of another kind (cloth, a soft body, a shape-matched object), a moving
// collider, a dynamic or moving rigid body or rod; and while a joint holds one of its grains. A sleeping island wakes whole, with its still
// time reset, as soon as an awake particle, a moving collider or a body comes within contact reach
// of one of its grains — before the step that would touch it is solved, so the step sees the
// island as it would have without sleeping. (The islands and the sleep timer are those of rigid
// body engines, e.g. Box2D; islands are found by union-find over the step's contact candidates,
// serially, so the result does not depend on the thread count.)
#include <vector>

#include "moreau/math/types.hpp"

namespace moreau {

struct Model;
struct State;

struct GrainSleepState {
  std::vector<Vec3> still_from;  // m, per particle: where its stillness began (asleep: where it sleeps)
  std::vector<Real> still_time;  // s, per particle: how long it has stayed near there
  std::vector<Index> island;     // per particle: its sleeping island (the island's smallest particle), -1 awake
  Index asleep_count = 0;        // sleeping grains
  std::vector<Index> awake;      // the particles not asleep, in order: those a substep moves
  // Buffers of the island search, kept between steps (no allocation per step).
  std::vector<Index> parent;
  std::vector<char> keeps_awake, island_awake;

  bool asleep(Index p) const { return island[p] >= 0; }
  /// Whether the shape-matching cluster whose first particle is `first` sleeps: a clump sleeps and
  /// wakes whole (cheap while nothing sleeps).
  bool cluster_asleep(Index first) const { return asleep_count > 0 && asleep(first); }
  /// Rebuilds `awake` from `island` (after grains fell asleep or woke).
  void list_awake();
  /// Every particle awake and just become still at `positions`.
  void resize(const std::vector<Vec3>& positions);
};

/// Whether a body moves or can be moved, so that a sleeping grain near it is a contact candidate
/// (which wakes its island): dynamic, or moving kinematically.
bool body_wakes_grains(const Model& model, const State& state, Index body);

/// Wakes every sleeping island that this step's contact candidates reach: a pair of an awake
/// particle and a sleeping grain, a sleeping grain's candidate with a moving collider or with a
/// body. Returns whether any island woke (the candidates must then be sought again).
bool wake_reached_islands(State& state);

/// Wakes the island of every sleeping grain that was moved or given a velocity from outside the
/// step (a World state array written between steps); a step calls it first.
void wake_moved_grains(const Model& model, State& state);

/// After a step: updates the grains' stillness and puts to sleep every island that has been
/// still for settings.sleep.time and touches nothing that stays awake.
void update_grain_sleep(const Model& model, State& state);

}  // namespace moreau
