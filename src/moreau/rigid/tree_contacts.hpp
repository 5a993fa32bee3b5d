#pragma once
// Rigid contacts of a joint tree's bodies, solved inside the tree's direct solve (joint_tree.hpp)
// instead of by Gauss-Seidel after it: contacts with bodies the solve does not move (the world,
// fixed and kinematic bodies) and contacts between two tree bodies (rod on rod, a rope's turns).
//
// Why: a rope of light segments wound on a turning drum and holding a heavy box. The direct solve
// makes the rope inextensible, then Gauss-Seidel pushes each segment out of the drum seeing only
// that segment's mass; the next direct solve pulls it back in. The two projections undo each
// other: the rope stretched 0.6-2.4 % in 0.05 s instead of 0.05 % and was thrown off the drum.
//
// Rows: each contact point has rows G (3 x 6 per tree body: the normal and the two tangents of
// contact_rows.hpp, as dC/d(dx, dtheta) of that body), values C and multipliers lambda. A rigid row
// has no compliance; each gets the tiny compliance
//   alpha~_r = kContactRegularization w_r,   w_r = sum over the bodies of 1/m + (o x d_r) . I^-1 (o x d_r)
// (alpha~ = alpha/h^2 is an inverse mass): the point then gives way by kContactRegularization
// of what the bodies alone would move, 4e-12 m under the rope's 7 N per segment, and a leaf row
// can be eliminated.
//
// Leaves (one tree body): each point is one more leaf of the tree, hanging from its body's node.
// Eliminating it before its body (D_c = -alpha~, H_c,body = -G):
//   D_body += G^T alpha~^-1 G,   s_body -= G^T alpha~^-1 (C + alpha~ lambda)
// and after the tree solve, with y the body's (dx, dtheta): dlambda = -(C + alpha~ lambda + G y) / alpha~.
//
// Links (two tree bodies) would close loops in the tree; they are taken by a Schur complement.
// With the tree (leaves included) factored as A, its solution y0 for the joints' right-hand side,
// and Y = A^-1 G^T (one tree solve per link row, G^T placing each row's blocks on its two bodies):
//   (G Y + alpha~) dlambda = -(C + alpha~ lambda + G y0),   y = y0 + Y dlambda,
// a small dense system (G Y is the links' Delassus matrix through the whole tree).
//
// Rows are unilateral: an active set decides which are solved. A point takes part if it penetrates
// or already pushes (lambda_n > 0); it starts sticking (all three rows) when it has static
// friction. After a solve, a point whose lambda_n fell below zero lets go, and a sticking point
// whose |lambda_t| exceeds mu_s lambda_n slides; either releases what it held (a known
// dlambda = -lambda on the released rows, added to its bodies' right-hand sides as G^T dlambda),
// and all is solved again, until the set holds. Sliding points get dynamic friction in the
// velocity pass, as the Gauss-Seidel contacts do (rigid_contact_projection.hpp).
//
// Only a tree that nothing else moves in the iterations takes its contacts into the direct solve:
// one that touches a dynamic body outside the forest (closer than kSharingGap at the substep's
// start), has a particle contact this step, or on which Gauss-Seidel projects a joint's rows (a
// loop's, a limit's or a drive's), keeps all its contacts with Gauss-Seidel for the substep, and so
// does a tree touching such a tree.
// Mixed, the two projections ratchet: a rod lying on the ground under a crossing rod, whose
// Gauss-Seidel contact pushed a segment down while the direct solve only pushed penetrating points
// up, arched 0.37 mm off the ground.
#include <array>
#include <vector>

#include <Eigen/Core>

#include "moreau/constraints/body_rows.hpp"
#include "moreau/constraints/substep_start.hpp"
#include "moreau/math/types.hpp"
#include "moreau/rigid/tree_factorization.hpp"

namespace moreau {

struct Model;
struct State;

inline constexpr Real kContactRegularization = 1e-6;
inline constexpr Real kSharingGap = 1e-3;  // m

/// Marks the manifolds solved in the direct solve this substep (RigidManifold::with_joints): a
/// tree body touching a body that is not dynamic, or two tree bodies, in trees that are not shared
/// (see above). Call at the substep's start.
void choose_tree_contacts(const Model& model, State& state);

/// One point of a tree manifold, linearised at the bodies' poses.
struct TreeContactPoint {
  Index manifold = -1, point = -1;      // state.rigid_contacts: the manifold and its point in it
  std::array<Index, 2> node{-1, -1};    // the bodies' nodes in the forest (-1: not a tree body)
  Real static_friction = 0;
  std::array<BodyRows::Jacobian, 2> G;  // point rows (body_rows.hpp) per body: normal, tangent 1, tangent 2
  Vec3 C, alpha_tilde, lambda;          // m; 1/kg; kg m (accumulated this substep)
  bool active = false, sticking = false;

  bool is_link() const { return node[0] >= 0 && node[1] >= 0; }
  int solved_rows() const { return !active ? 0 : sticking ? 3 : 1; }
};

/// The tree contacts of one linearisation.
class TreeContacts {
 public:
  /// Linearises every point of the tree manifolds at the current poses (slip measured from
  /// `start`) and picks the initial active set.
  TreeContacts(const Model& model, State& state, const SubstepStart& start);

  bool empty() const { return points_.empty(); }
  /// Largest |C + alpha~ lambda| of the solved rows (m).
  Real residual() const;
  /// Adds the leaves to their bodies' diagonal blocks and right-hand sides, and the released rows'
  /// known impulses to the right-hand sides (node-indexed).
  void add_to(std::vector<TreeBlock>& diagonal, std::vector<TreeColumn>& rhs) const;
  /// Given the factored tree and its solution y0 (node-indexed), solves the links' Schur complement
  /// and turns `solution` into y0 + Y dlambda.
  void solve_links(const TreeFactorization& tree, std::vector<TreeColumn>& solution);
  /// Judges the active set against a solution (node-indexed: (dx, dtheta) on body nodes); returns
  /// whether it holds. If not, the set is changed for the next solve.
  bool holds(const std::vector<TreeColumn>& solution);
  /// Adds the solution's multipliers to the points and marks touching and sliding.
  void accept(const std::vector<TreeColumn>& solution, State& state) const;

 private:
  /// The point's dlambda for a solution: leaves from their body's motion, links from the last
  /// solve_links, released rows -lambda.
  Vec3 dlambda(size_t k, const std::vector<TreeColumn>& solution) const;

  std::vector<TreeContactPoint> points_;
  std::vector<Vec3> link_dlambda_;  // per point (links only): from the last solve_links
};

}  // namespace moreau
