#pragma once
// Direct linear-time solve of the joints' equality rows on tree-structured joint graphs (Deul,
// Kugelstadt, Weiler, Bender 2018, "Direct Position-Based Solver for Stiff Rods", after Baraff
// 1996, "Linear-Time Dynamics using Lagrange Multipliers").
//
// Gauss-Seidel over joints propagates a correction one joint per pass, so a light chain holding a
// heavy weight stretches like a soft spring. Here each XPBD iteration instead solves the whole
// linearised system of every joint's equality rows at once and exactly:
//
//   [ M    -J^T   ] [dx    ]   [ 0                ]      M = diag(m I, I_world) per body,
//   [ -J   -alpha~] [dlambda] = [ C + alpha~ lambda ]     alpha~ = alpha / h^2 per row,
//
// i.e. dlambda = -(J M^-1 J^T + alpha~)^-1 (C + alpha~ lambda) and dx = M^-1 J^T dlambda, the
// XPBD update of all joints together. The graph whose nodes are bodies and joints, with an edge
// where a joint acts on a body, is a forest; ordered so every node precedes its parent, the
// symmetric matrix factors without fill-in:
//   factor   D_i = H_ii - sum_children H_ci^T D_c^-1 H_ci,  J_i = D_i^-1 H_i,parent
//   forward  s_i = b_i - sum_children J_c^T s_c             (leaves to roots)
//   backward s_i = D_i^-1 s_i - J_i s_parent                (roots to leaves)
// after which s holds dx on body nodes and dlambda on joint nodes.
//
// The trees' rigid contacts join the same solve (tree_contacts.hpp).
//
// Rows per joint: spherical 3 (anchors), fixed 6 (anchors, orientation), hinge 5 (anchors, axis
// alignment), distance with min = max 1. Limits, drives and the other joint types stay in the
// Gauss-Seidel pass (solvers/xpbd/joint_projection.cpp). Only dynamic bodies are nodes; the world, fixed and kinematic
// bodies are not, so a joint to them has one neighbour and becomes its component's root. A joint
// that would close a loop (between bodies already connected, or a second joint to the world in
// a component) stays with Gauss-Seidel: loops are closed iteratively.
#include <vector>

#include "moreau/math/types.hpp"
#include "moreau/constraints/joints/joint.hpp"
#include "moreau/constraints/substep_start.hpp"
#include "moreau/rigid/rigid_bodies.hpp"

namespace moreau {

struct Model;
struct State;

struct JointTreeNode {
  bool is_body = true;
  Index index = -1;   // rigid body or joint
  Index parent = -1;  // node index; -1 for a root
};

struct JointForest {
  std::vector<JointTreeNode> nodes;   // every node precedes its parent (leaves first)
  std::vector<char> joint_in_tree;    // per joint: its equality rows are solved here
  std::vector<Index> body_node;       // per rigid body: its node, or -1
  std::vector<Index> body_tree;       // per rigid body: its tree (the root's node), or -1
  std::vector<char> tree_has_loose_joints;  // per root node: Gauss-Seidel projects some joint's rows on the tree

  bool empty() const { return nodes.empty(); }
  bool in_tree(size_t joint) const { return joint < joint_in_tree.size() && joint_in_tree[joint]; }
  Index node_of_body(Index b) const { return b >= 0 && static_cast<size_t>(b) < body_node.size() ? body_node[b] : -1; }
  Index tree_of_body(Index b) const { return b >= 0 && static_cast<size_t>(b) < body_tree.size() ? body_tree[b] : -1; }
};

/// Builds the forest from the joints in scene order (see the file comment for loops).
JointForest build_joint_forest(const RigidBodyModel& bodies, const std::vector<Joint>& joints);

// One linearised solve is a Newton step: exact for the linear part, but a light chain under high
// tension has stiff sideways modes through the constraints' curvature (geometric stiffness), which
// one step treats explicitly; re-linearising until |C + alpha~ lambda| < kDirectTolerance (m or
// rad) makes the projection implicit in them too. A released 100-link chain holding 100 kg tears
// at 20 substeps with one solve per substep and keeps 3e-7 m with two.
inline constexpr Real kDirectTolerance = 1e-9;
inline constexpr int kMaxDirectPasses = 8;

/// Solves every tree joint's equality rows and the trees' contacts, re-linearising up to
/// kMaxDirectPasses times until they hold; accumulates their multipliers. Returns the number of
/// linear solves done.
/// `start` holds the poses at the substep start (for damped rows, body_rows.hpp).
int solve_joint_forest(const Model& model, State& state, const SubstepStart& start, Real h);

}  // namespace moreau
