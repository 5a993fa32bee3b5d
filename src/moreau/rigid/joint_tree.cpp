#include "moreau/rigid/joint_tree.hpp"

#include <numeric>

#include "moreau/model/model.hpp"
#include "moreau/model/state.hpp"
#include "moreau/rigid/body_handle.hpp"
#include "moreau/rigid/tree_contacts.hpp"
#include "moreau/rigid/tree_factorization.hpp"

namespace moreau {

namespace {

using Block = TreeBlock;
using Column = TreeColumn;
using RowJacobian = Eigen::Matrix<Real, Eigen::Dynamic, 6, 0, 6, 6>;

bool is_tree_body(const RigidBodyModel& bodies, const JointEnd& e) {
  return e.kind == BodyEndKind::body && bodies.is_dynamic(e.index);
}

// A joint's equality rows linearised at the current poses (the joint type's own blocks, in its
// order): C, alpha~, the accumulated multipliers and dC/d(dx, dtheta) of each end (dtheta a
// world-space rotation vector), with where each block's multipliers live.
struct JointRows {
  Column c, alpha_tilde, lambda;
  std::array<RowJacobian, 2> jacobian;
  struct Block {
    int slot = 0, offset = 0, size = 0;
  };
  std::array<Block, 2> blocks;
  int block_count = 0;
};

// Stacks the blocks a joint hands on into its JointRows. Rows a joint leaves out (a distance
// joint's at zero length) stay zero.
class RowStack final : public BodyRowSink {
 public:
  RowStack(JointRows& rows, const JointMultipliers& lambda, Real h) : rows_(rows), lambda_(lambda), h_(h) {}
  void take(const BodyRows& block) override {
    const int n = block.size();
    if (n == 3)
      place<3>(block);
    else
      place<Eigen::Dynamic>(block);
    rows_.blocks[rows_.block_count++] = {block.slot, next_, n};
    next_ += n;
  }
  int rows_taken() const { return next_; }

 private:
  // Fixed-size copies for the common 3-row blocks (attachment, orientation).
  template <int N>
  void place(const BodyRows& block) {
    const int n = block.size();
    BodyRows::Vector C = block.C, alpha_tilde = block.compliance / (h_ * h_);
    apply_xpbd_damping(block, h_, C, alpha_tilde);
    rows_.c.segment<N>(next_, n) = C;
    rows_.alpha_tilde.segment<N>(next_, n) = alpha_tilde;
    rows_.lambda.segment<N>(next_, n) = Eigen::Map<const Eigen::Matrix<Real, N, 1>>(lambda_.data() + block.slot, n);
    for (int e = 0; e < 2; ++e) rows_.jacobian[e].middleRows<N>(next_, n) = block.jacobian[e];
  }

  JointRows& rows_;
  const JointMultipliers& lambda_;
  Real h_;
  int next_ = 0;
};

JointRows joint_rows_now(const Joint& j, const JointMultipliers& lambda, const State& state, const SubstepStart& start,
                         Real h) {
  const int n = direct_rows(j);
  const Real inv_h2 = 1 / (h * h);
  JointRows rows;
  rows.c.resize(n);
  rows.alpha_tilde.resize(n);
  rows.lambda.resize(n);
  for (auto& jac : rows.jacobian) jac.resize(n, 6);
  RowStack stack(rows, lambda, h);
  joint_rows({state, j, h, 0, JointRowSet::equality, &start}, stack);
  if (const int taken = stack.rows_taken(); taken < n) {
    rows.c.tail(n - taken).setZero();
    rows.alpha_tilde.tail(n - taken).setConstant(j.compliance * inv_h2);
    rows.lambda.tail(n - taken).setZero();
    for (auto& jac : rows.jacobian) jac.bottomRows(n - taken).setZero();
  }
  return rows;
}

void add_to_lambdas(const JointRows& rows, const Column& d, JointMultipliers& lambda) {
  for (int b = 0; b < rows.block_count; ++b) {
    const JointRows::Block& block = rows.blocks[b];
    Eigen::Map<BodyRows::Vector>(lambda.data() + block.slot, block.size) += d.segment(block.offset, block.size);
  }
}

// Union-find over bodies, remembering which joint ties each component to the world.
struct Components {
  std::vector<Index> parent, grounding_joint;
  explicit Components(Index n) : parent(n), grounding_joint(n, -1) { std::iota(parent.begin(), parent.end(), 0); }
  Index find(Index b) {
    while (parent[b] != b) b = parent[b] = parent[parent[b]];
    return b;
  }
};

}  // namespace

JointForest build_joint_forest(const RigidBodyModel& bodies, const std::vector<Joint>& joints) {
  JointForest forest;
  forest.joint_in_tree.assign(joints.size(), 0);
  Components components(bodies.count());
  std::vector<std::vector<Index>> body_joints(bodies.count());
  for (size_t k = 0; k < joints.size(); ++k) {
    const Joint& j = joints[k];
    if (direct_rows(j) == 0) continue;
    if (j.ends[0].kind == BodyEndKind::particle || j.ends[1].kind == BodyEndKind::particle) continue;
    const bool tree_a = is_tree_body(bodies, j.ends[0]), tree_b = is_tree_body(bodies, j.ends[1]);
    if (tree_a && tree_b) {
      const Index ra = components.find(j.ends[0].index), rb = components.find(j.ends[1].index);
      if (ra == rb) continue;  // closes a loop between bodies
      if (components.grounding_joint[ra] >= 0 && components.grounding_joint[rb] >= 0) continue;  // via the world
      components.parent[ra] = rb;
      components.grounding_joint[rb] = std::max(components.grounding_joint[ra], components.grounding_joint[rb]);
    } else if (tree_a || tree_b) {
      const Index r = components.find(j.ends[tree_a ? 0 : 1].index);
      if (components.grounding_joint[r] >= 0) continue;  // a second joint to the world closes a loop
      components.grounding_joint[r] = static_cast<Index>(k);
    } else {
      continue;  // nothing dynamic to move
    }
    forest.joint_in_tree[k] = 1;
    for (const JointEnd& e : j.ends)
      if (is_tree_body(bodies, e)) body_joints[e.index].push_back(static_cast<Index>(k));
  }

  // Breadth-first from each component's root (its joint to the world, else its first body), then
  // reversed so that every node precedes its parent.
  std::vector<JointTreeNode> order;
  std::vector<char> body_seen(bodies.count(), 0), joint_seen(joints.size(), 0);
  auto visit_from = [&](JointTreeNode root) {
    size_t head = order.size();
    order.push_back(root);
    (root.is_body ? body_seen : joint_seen)[root.index] = 1;
    for (; head < order.size(); ++head) {
      const JointTreeNode node = order[head];
      const Index here = static_cast<Index>(head);
      if (node.is_body) {
        for (Index k : body_joints[node.index])
          if (!joint_seen[k]) {
            joint_seen[k] = 1;
            order.push_back({false, k, here});
          }
      } else {
        for (const JointEnd& e : joints[node.index].ends)
          if (is_tree_body(bodies, e) && !body_seen[e.index]) {
            body_seen[e.index] = 1;
            order.push_back({true, e.index, here});
          }
      }
    }
  };
  for (Index b = 0; b < bodies.count(); ++b) {
    if (body_joints[b].empty() || body_seen[b]) continue;
    const Index grounding = components.grounding_joint[components.find(b)];
    visit_from(grounding >= 0 ? JointTreeNode{false, grounding, -1} : JointTreeNode{true, b, -1});
  }
  const Index n = static_cast<Index>(order.size());
  forest.nodes.resize(n);
  forest.body_node.assign(bodies.count(), -1);
  for (Index i = 0; i < n; ++i) {
    JointTreeNode node = order[n - 1 - i];
    if (node.parent >= 0) node.parent = n - 1 - node.parent;
    forest.nodes[i] = node;
    if (node.is_body) forest.body_node[node.index] = i;
  }
  // Roots come last: each node's tree is its parent's.
  std::vector<Index> tree(n);
  for (Index i = n; i-- > 0;) tree[i] = forest.nodes[i].parent < 0 ? i : tree[forest.nodes[i].parent];
  forest.body_tree.assign(bodies.count(), -1);
  for (Index b = 0; b < bodies.count(); ++b)
    if (forest.body_node[b] >= 0) forest.body_tree[b] = tree[forest.body_node[b]];
  forest.tree_has_loose_joints.assign(n, 0);
  for (size_t k = 0; k < joints.size(); ++k) {
    if (forest.joint_in_tree[k] && !has_other_rows(joints[k])) continue;  // limits and drives: Gauss-Seidel
    for (const JointEnd& e : joints[k].ends)
      if (e.kind == BodyEndKind::body && forest.tree_of_body(e.index) >= 0)
        forest.tree_has_loose_joints[forest.tree_of_body(e.index)] = 1;
  }
  return forest;
}

namespace {

// The buffers of a direct pass.
struct DirectPassScratch {
  std::vector<JointRows> rows;
  std::vector<Block> diagonal, coupling, pivots;
  std::vector<Column> rhs, solution;
  TreeFactorization factorization;
};

// The active set of the tree contacts changes at most this many times per linearisation; a set
// still changing after that is taken as it stands and the next pass goes on from there.
constexpr int kMaxActiveSetSolves = 16;

// One linearised solve (a Newton step on every tree joint's equality rows and the tree contacts'
// active rows), skipped when the largest |C + alpha~ lambda| is already below the tolerance;
// returns whether it solved.
bool direct_pass(const Model& model, State& state, const SubstepStart& start, Real h) {
  const JointForest& forest = model.joint_forest;
  const size_t n = forest.nodes.size();
  TreeContacts contacts(model, state, start);
  Real residual = contacts.residual();

  // Diagonal blocks H_ii (M for a body, -alpha~ for a joint) and right-hand sides b_i.
  // Reused from pass to pass (freeing and taking back these blocks every pass cost the steel rod
  // benchmark a sixth of its time in page faults); each thread that runs a solve has its own.
  thread_local DirectPassScratch scratch;
  std::vector<JointRows>& rows = scratch.rows;
  std::vector<Block>& diagonal = scratch.diagonal;
  std::vector<Column>& rhs = scratch.rhs;
  rows.resize(n);
  diagonal.resize(n);
  rhs.resize(n);
  for (size_t i = 0; i < n; ++i) {
    const JointTreeNode& node = forest.nodes[i];
    if (node.is_body) {
      const Index b = node.index;
      const Mat3 R = state.rigid.orientation[b].toRotationMatrix();
      diagonal[i].setZero(6, 6);
      diagonal[i].topLeftCorner<3, 3>() = model.rigid.body_mass[b] * Mat3::Identity();
      diagonal[i].bottomRightCorner<3, 3>() = R * model.rigid.body_inertia[b].asDiagonal() * R.transpose();
      rhs[i].setZero(6);
    } else {
      const Joint& j = model.joints[node.index];
      rows[i] = joint_rows_now(j, state.joint_lambda[node.index], state, start, h);
      diagonal[i] = -Block(rows[i].alpha_tilde.asDiagonal());
      rhs[i] = rows[i].c + rows[i].alpha_tilde.cwiseProduct(rows[i].lambda);
      residual = std::max(residual, rhs[i].cwiseAbs().maxCoeff());
    }
  }
  if (residual <= kDirectTolerance) return false;
  // Off-diagonal H_i,parent = -J (rows x 6) below a body, -J^T (6 x rows) below a joint.
  std::vector<Block>& coupling = scratch.coupling;
  coupling.resize(n);
  for (size_t i = 0; i < n; ++i) {
    const JointTreeNode& node = forest.nodes[i];
    if (node.parent < 0) continue;
    const size_t joint_node = node.is_body ? node.parent : i;
    const Index body = node.is_body ? node.index : forest.nodes[node.parent].index;
    const Joint& j = model.joints[forest.nodes[joint_node].index];
    const int slot = j.ends[0].kind == BodyEndKind::body && j.ends[0].index == body ? 0 : 1;
    const RowJacobian& jac = rows[joint_node].jacobian[slot];
    coupling[i] = node.is_body ? Block(-jac.transpose()) : Block(-jac);
  }

  // The contacts join the solve (tree_contacts.hpp); solved again while their active set changes.
  std::vector<Column>& s = scratch.solution;
  for (int attempt = 1;; ++attempt) {
    scratch.pivots = diagonal;
    s = rhs;
    contacts.add_to(scratch.pivots, s);
    scratch.factorization.factor(forest, scratch.pivots, coupling);
    scratch.factorization.solve(s);
    contacts.solve_links(scratch.factorization, s);
    if (contacts.empty() || attempt == kMaxActiveSetSolves || contacts.holds(s)) break;
  }

  for (size_t i = 0; i < n; ++i) {
    const JointTreeNode& node = forest.nodes[i];
    if (node.is_body) {
      const BodyHandle body = rigid_body_handle(model.rigid, state.rigid, node.index);
      *body.position += s[i].head<3>();
      body.rotate_by(s[i].tail<3>());
    } else {
      add_to_lambdas(rows[i], s[i], state.joint_lambda[node.index]);
    }
  }
  if (!contacts.empty()) contacts.accept(s, state);
  return true;
}

}  // namespace

int solve_joint_forest(const Model& model, State& state, const SubstepStart& start, Real h) {
  if (model.joint_forest.empty()) return 0;
  int passes = 0;
  while (passes < kMaxDirectPasses && direct_pass(model, state, start, h)) ++passes;
  return passes;
}

}  // namespace moreau
