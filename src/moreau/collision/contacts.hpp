#pragma once
// Contacts of particles with colliders and with each other.
//
// Non-penetration (Mueller et al. 2020, "Detailed Rigid Body Simulation with XPBD", sec. 3.5;
// particles are bodies without rotation):
//   collider:  C = phi(x) - g >= 0             grad = n (outward collider normal), g = collider gap
//   particles: C = |xi - xj| - (ri + rj) >= 0  grad_xi = n = (xi - xj)/|xi - xj|, grad_xj = -n
//   compliance 0; applied only while C < 0; lambda_n accumulates over the substep's iterations.
// Static friction (position level): the relative tangential displacement over the substep,
//   dp_t, is cancelled when |dp_t| / (w1 + w2) < mu_s lambda_n.
// Velocity pass (once per substep, after v = (x - x_start)/h):
//   dynamic friction  dv = -v_t/|v_t| min(mu_k (w1 + w2) lambda_n / h, |v_t|)
//     (the normal impulse of the substep is lambda_n / h; we use this dimensionally consistent
//      reading of Mueller 2020, eq. 30, whose f_n h mixes force and velocity)
//   restitution       dv = n (-v_n + max(-e vbar_n, 0)),  e = 0 when |v_n| <= 2 |g| h
//   each applied as an impulse split by inverse mass.
// Candidates are gathered once per step within r_i + r_j + k dt (|v| + dt |g|) (k = 2; Mueller 2020
// uses k dt |v|, we add the fall under gravity so resting contacts are never missed) and re-evaluated
// every substep.
#include <vector>

#include "moreau/constraints/constraint_batches.hpp"
#include "moreau/solvers/xpbd/substep_context.hpp"
#include "moreau/geometry/spatial_hash.hpp"

namespace moreau {

struct Model;
struct State;

struct ColliderContacts {
  std::vector<Index> particle;        // sorted by particle
  std::vector<Index> collider;
  std::vector<Index> group_offsets;   // contacts of one particle: [group_offsets[g], group_offsets[g+1])
  std::vector<Real> lambda_normal;    // kg m, accumulated over the substep
  std::vector<Vec3> normal;           // outward normal at the last projection
  std::vector<Real> static_friction, dynamic_friction, restitution;  // combined coefficients

  size_t size() const { return particle.size(); }
  void clear();
};

struct ParticleContacts {
  std::vector<std::array<Index, 2>> pair;
  ColorBatches batches;
  std::vector<Real> lambda_normal;
  std::vector<Vec3> normal;           // (x_a - x_b)/|x_a - x_b| at the last projection
  std::vector<Real> static_friction, dynamic_friction, restitution;

  size_t size() const { return pair.size(); }
  void clear();
};

/// Reused buffers of contact detection (no allocation once their capacity suffices).
struct ContactScratch {
  SpatialHash hash;
  std::vector<Index> contact_particles;
  std::vector<std::vector<std::array<Index, 2>>> thread_pairs;
  std::vector<std::uint64_t> particle_colors;
  std::vector<int> pair_color;
  std::vector<Index> order;
  std::vector<Index> color_count;
};

/// Gathers (particle, collider) candidates for the coming step.
void detect_collider_contacts(const Model& model, State& state);

/// Gathers particle pairs for the coming step (on `threads` threads) and sorts them into colour batches.
void detect_particle_contacts(const Model& model, State& state, int threads);

/// Projections inside a substep; call inside an OpenMP parallel region. `substep_end_time` places
/// kinematic colliders.
void project_collider_contacts(const Model& model, State& state, const SubstepContext& s, Real substep_end_time);
void project_particle_contacts(const Model& model, State& state, const SubstepContext& s);

/// Relative-velocity change dv of one contact that pushed this substep (the two laws above): v_rel
/// and v_rel_before now and after prediction, n the normal, lambda_n the substep's normal
/// multiplier, w the summed inverse masses along n, g = |gravity| (the resting-speed cut-off).
Vec3 contact_velocity_change(const Vec3& v_rel, const Vec3& v_rel_before, const Vec3& n, Real lambda_n, Real w,
                             Real mu_k, Real e, Real h, Real g);

/// Velocity pass: dynamic friction and restitution of the contacts active in this substep.
void collider_contact_velocities(const Model& model, State& state, Real h);
void particle_contact_velocities(const Model& model, State& state, Real h);

}  // namespace moreau
