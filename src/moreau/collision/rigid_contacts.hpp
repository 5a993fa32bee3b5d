#pragma once
// Contacts between rigid bodies (colliders take part as kinematic bodies). Position-level
// contacts with static friction and a velocity pass for dynamic friction and restitution, after
// Mueller et al. 2020, sec. 3.5-3.6, solved per contact manifold.
//
// Once per step: a sweep-and-prune broad phase over body bounds expanded by k dt |v| (k = 2) and
// the narrow phase (narrow_phase.hpp) with the same margin give each touching pair a manifold of
// up to four points stored as body-frame cores. Every substep and iteration, per manifold:
//   point i  p_a = x_a + q_a core_a - r_a n,  p_b = x_b + q_b core_b + r_b n
//   normal   C_i = d_i = (p_a - p_b) . n_i >= 0, compliance 0
//   static   C = dp . t = 0 for two tangents t, dp = (p_a - pbar_a) - (p_b - pbar_b) + s the slip of
//   friction the two material points over the substep plus s, the slip left over since the point
//            began to stick; it holds while |lambda_t| < mu_s lambda_n
// Mueller 2020 counts slip per substep only. What one Gauss-Seidel pass leaves unsolved then
// becomes permanent, and a column of eight unit boxes with mu = 0.5 rocked itself over within a
// second (energy rising) while a 2D pyramid crept sideways. Carrying s over the substeps, and over
// steps for the same point of the same pair (matched by its body-frame cores), makes static
// friction a position constraint that holds; s is cleared when the manifold slides or the point
// separates.
// The rows of a manifold's penetrating points are constraints/contact_rows.hpp; XPBD solves them
// as one block and applies dynamic friction and restitution in a velocity pass
// (solvers/xpbd/rigid_contact_projection.hpp).
// Coefficients combine as the mean of the two bodies' (Mueller 2020).
#include <tuple>
#include <vector>

#include "moreau/collision/narrow_phase.hpp"

namespace moreau {

struct Model;
struct State;

struct RigidContactPoint {
  ContactGeometry geometry;
  Real lambda_normal = 0;                // kg m, this substep
  Vec2 lambda_tangent = Vec2::Zero();    // kg m, this substep: static friction held by the direct solve
  Vec3 normal = Vec3::UnitY();           // world, at the last projection
  Vec3 offset_a = Vec3::Zero(), offset_b = Vec3::Zero();  // world, contact points minus centres
  Vec3 material_a = Vec3::Zero(), material_b = Vec3::Zero();  // body frames, the points at the last projection
  Vec3 stuck_slip = Vec3::Zero();        // world, tangential slip since the point began to stick
  Vec3 row_impulse = Vec3::Zero();       // kg m: a velocity-level solver's impulses times h on the
                                         // normal and the two tangent rows, its warm start
  bool touching = false;
};

struct RigidManifold {
  Index body_a = -1, body_b = -1;
  Index first = 0, count = 0;            // points [first, first + count)
  NormalFrame frame = NormalFrame::body_b;
  Real static_friction = 0, dynamic_friction = 0, restitution = 0;
  Real adhesion = 0;                     // N per point: the larger of the two bodies' (either glue holds)
  // Per substep.
  bool with_joints = false;              // xpbd: solved in the joints' direct solve (tree_contacts.hpp)
  bool touching = false;                 // a point pushed this substep
  bool sliding = false;                  // friction rows dropped at the last projection
};

/// Reused buffers of the broad phase.
struct RigidBroadPhaseScratch {
  std::vector<Vec3> lower, upper;            // expanded world bounds per body
  std::vector<Index> order;                  // bodies sorted by lower x
  std::vector<Real> margin;                  // per body, m
  std::vector<std::array<Index, 2>> pairs;
  std::vector<std::vector<std::array<Index, 2>>> thread_pairs;  // the sweep's finds per thread, then merged
  std::vector<std::vector<ContactManifold>> pair_manifolds;  // per pair: one, or one per mesh triangle
  std::vector<RigidManifold> previous_manifolds;  // last step's, to carry stuck slip over
  std::vector<RigidContactPoint> previous_points;

  // Checkpoints hold everything but the per-thread lists, whose number is the last step's thread
  // count (it follows the machine's load) and whose contents are merged into `pairs` anyway.
  auto archive_members() { return std::tie(lower, upper, order, margin, pairs, pair_manifolds, previous_manifolds, previous_points); }
  auto archive_members() const {
    return std::tie(lower, upper, order, margin, pairs, pair_manifolds, previous_manifolds, previous_points);
  }
};

struct RigidContacts {
  std::vector<RigidManifold> manifolds;
  std::vector<RigidContactPoint> points;
  RigidBroadPhaseScratch scratch;
};

/// Broad and narrow phase for the coming step, the narrow phase on `threads` threads.
void detect_rigid_contacts(const Model& model, State& state, int threads);

/// Contact points in touch at the end of the last substep involving `object` (-1: any).
Index touching_contact_count(const Model& model, const State& state, Index object);

}  // namespace moreau
