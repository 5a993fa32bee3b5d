#pragma once
// Detection of particle contacts, with colliders and with each other: the candidate lists a step's
// solver evaluates (constraint rows: constraints/particle_contact_rows.hpp; XPBD's projection:
// solvers/xpbd/particle_contact_projection.hpp).
//
// Candidates are gathered once per step and re-evaluated every substep: with a collider within
// r + k dt (|v - v_c| + dt |g|) (k = 2; Mueller et al. 2020, sec. 3.5, uses k dt |v|; we add the
// fall under gravity so resting contacts are never missed); two particles within
// r_i + r_j + g + min(k dt |v_i - v_j|, r_i + r_j), g the reach of a bond between cohesive grains.
#include <array>
#include <vector>

#include "moreau/constraints/compliant_contact.hpp"
#include "moreau/constraints/tile_batches.hpp"
#include "moreau/geometry/cell_grid.hpp"

namespace moreau {

struct Model;
struct State;

struct ColliderContacts {
  std::vector<Index> particle;        // sorted by particle
  std::vector<Index> collider;
  std::vector<Index> group_offsets;   // contacts of one particle: [group_offsets[g], group_offsets[g+1])
  std::vector<Real> lambda_normal;    // kg m, accumulated over the substep
  std::vector<Vec3> lambda_friction;  // kg m: a grain's friction impulse, accumulated over the substep
  std::vector<Vec3> lambda_rolling;   // kg m^2: a grain's rolling-resistance impulse, likewise
  std::vector<Vec3> normal;           // outward normal at the last projection
  std::vector<Real> static_friction, dynamic_friction, restitution;  // combined coefficients
  std::vector<Real> adhesion;         // N: the larger of the two sides' (glue on either holds; nmd)
  std::vector<Real> rolling_resistance;  // mu_r of the particle (grains; 0 for particles that do not turn)
  std::vector<ContactSpring> spring;     // a grain's viscoelastic contact (compliance 0: hard)

  size_t size() const { return particle.size(); }
  void clear();
};

struct ParticleContacts {
  std::vector<std::array<Index, 2>> pair;
  TileBatches batches;  // the pairs by tile of the pair search's grid (constraints/tile_batches.hpp)
  std::vector<Real> lambda_normal;
  std::vector<Vec3> lambda_friction;  // kg m: friction impulse on the first particle when a side is a grain, this substep
  std::vector<Vec3> lambda_rolling;   // kg m^2: rolling-resistance impulse on the first particle, likewise
  std::vector<Vec3> normal;           // (x_a - x_b)/|x_a - x_b| at the last projection
  std::vector<Real> static_friction, dynamic_friction, restitution;
  std::vector<Real> cohesion;           // N: the largest pull of the pair's bond (0: none)
  std::vector<Real> cohesion_distance;  // m: the gap within which the bond pulls
  std::vector<Real> rolling_resistance;  // mu_r: the mean of two grains', a grain's against another particle
  std::vector<ContactSpring> spring;     // the mean of two grains', a grain's against another particle

  size_t size() const { return pair.size(); }
  void clear();
};

/// Reused buffers of contact detection (no allocation once their capacity suffices).
struct ContactScratch {
  CellGrid grid;
  std::vector<Vec3> contact_position;  // positions of the live contact particles (State::live_contact_particles), in order
  std::vector<Vec3> sorted_position;   // the same, and the particles' radii and ids, in the grid's order
  std::vector<Real> sorted_radius;
  std::vector<Index> sorted_particle;
  std::vector<Vec3> sorted_velocity;
  std::vector<Index> sorted_object;
  std::vector<char> sorted_fast;       // moves fast apart from the mean: searches its whole reach
  std::vector<char> sorted_moves;      // inverse mass > 0
  std::vector<char> sorted_asleep;
  std::vector<Real> bond_reach;        // m: bond_distance of objects a and b at [a * objects + b]
  std::vector<std::vector<std::array<Index, 2>>> thread_pairs;
  std::vector<Index> thread_first_cell;  // the first cell each thread searched from
  std::vector<int> thread_order;         // the threads by their first cell
  std::array<std::vector<std::array<Index, 2>>, kTileColors> color_tile_pairs;  // per colour, its tiles' pair ranges
  std::vector<Index> cell_pair_begin;  // the pairs found from cell c: [cell_pair_begin[c], cell_pair_begin[c+1])
  std::vector<std::array<Index, 2>> tiled_pairs;
};

/// Gathers (particle, collider) candidates for the coming step.
void detect_collider_contacts(const Model& model, State& state);

/// Gathers particle pairs for the coming step (on `threads` threads) and sorts them into tile batches.
void detect_particle_contacts(const Model& model, State& state, ContactScratch& scratch, int threads);

}  // namespace moreau
