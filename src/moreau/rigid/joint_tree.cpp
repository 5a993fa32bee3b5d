#include "moreau/rigid/joint_tree.hpp"

#include <Eigen/Cholesky>
#include <numeric>

#include "moreau/model/model.hpp"
#include "moreau/model/state.hpp"
#include "moreau/rigid/body_handle.hpp"
#include "moreau/rigid/joint_frames.hpp"

namespace moreau {

namespace {

// Small blocks of at most 6 x 6, stored inline (no heap allocation per node).
using Block = Eigen::Matrix<Real, Eigen::Dynamic, Eigen::Dynamic, 0, 6, 6>;
using Column = Eigen::Matrix<Real, Eigen::Dynamic, 1, 0, 6, 1>;
using RowJacobian = Eigen::Matrix<Real, Eigen::Dynamic, 6, 0, 6, 6>;

bool is_tree_body(const RigidBodyModel& bodies, const JointEnd& e) {
  return e.kind == JointEndKind::body && bodies.is_dynamic(e.index);
}

// A joint's equality rows linearised at the current poses: C, alpha~, the accumulated multipliers
// and dC/d(dx, dtheta) of each end (dtheta a world-space rotation vector).
struct JointRows {
  Column c, alpha_tilde, lambda;
  std::array<RowJacobian, 2> jacobian;
};

// Attachment C = p_a - p_b: dp = dx + dtheta x r = dx - [r]x dtheta.
void attachment_rows(const ConstEndView& a, const ConstEndView& b, JointRows& rows, int row) {
  rows.c.segment<3>(row) = a.anchor() - b.anchor();
  const Vec3 ra = a.anchor() - a.center, rb = b.anchor() - b.center;
  rows.jacobian[0].block<3, 3>(row, 0) = Mat3::Identity();
  rows.jacobian[0].block<3, 3>(row, 3) = -cross_matrix(ra);
  rows.jacobian[1].block<3, 3>(row, 0) = -Mat3::Identity();
  rows.jacobian[1].block<3, 3>(row, 3) = cross_matrix(rb);
}

// Fixed orientation C = 2 s vec(dq), dq = f_a f_b^-1 = (w, v), s = sign(w). Turning a by dtheta
// adds 1/2 [dtheta, 0] dq, whose vector part is (w I - [v]x) dtheta; turning b subtracts
// 1/2 dq [dtheta, 0], vector part (w I + [v]x) dtheta.
void orientation_rows(const ConstEndView& a, const ConstEndView& b, JointRows& rows, int row) {
  const Quat dq = a.frame() * b.frame().conjugate();
  const Real s = dq.w() >= 0 ? 1 : -1;
  rows.c.segment<3>(row) = 2 * s * dq.vec();
  rows.jacobian[0].block<3, 3>(row, 3) = s * (dq.w() * Mat3::Identity() - cross_matrix(dq.vec()));
  rows.jacobian[1].block<3, 3>(row, 3) = -s * (dq.w() * Mat3::Identity() + cross_matrix(dq.vec()));
}

// Hinge alignment C_k = y_k . e, e = x_b x x_a, for y_k the two axes of a across the hinge.
// de = x_b x (dtheta_a x x_a) + (dtheta_b x x_b) x x_a
//    = ((x_a.x_b) I - x_a x_b^T) dtheta_a - ((x_a.x_b) I - x_b x_a^T) dtheta_b,
// and y_k turns with a: d(y_k . e) gains (y_k x e) . dtheta_a.
void alignment_rows(const ConstEndView& a, const ConstEndView& b, JointRows& rows, int row) {
  const Vec3 xa = a.axis(0), xb = b.axis(0), e = xb.cross(xa);
  const Real cosine = xa.dot(xb);
  const Mat3 de_a = cosine * Mat3::Identity() - xa * xb.transpose();
  const Mat3 de_b = -(cosine * Mat3::Identity() - xb * xa.transpose());
  for (int k = 0; k < 2; ++k) {
    const Vec3 y = a.axis(1 + k);
    rows.c(row + k) = y.dot(e);
    rows.jacobian[0].block<1, 3>(row + k, 3) = y.transpose() * de_a + y.cross(e).transpose();
    rows.jacobian[1].block<1, 3>(row + k, 3) = y.transpose() * de_b;
  }
}

// Distance C = |d| - L along n = d / |d|: J_a = [n^T, (r_a x n)^T], J_b = -[n^T, (r_b x n)^T].
void distance_row(const ConstEndView& a, const ConstEndView& b, Real length, JointRows& rows) {
  const Vec3 d = a.anchor() - b.anchor();
  const Real len = d.norm();
  if (len <= 0) return;  // direction undefined: leave the row at C = 0, J = 0
  const Vec3 n = d / len, ra = a.anchor() - a.center, rb = b.anchor() - b.center;
  rows.c(0) = len - length;
  rows.jacobian[0] << n.transpose(), ra.cross(n).transpose();
  rows.jacobian[1] << -n.transpose(), -rb.cross(n).transpose();
}

JointRows joint_rows(const Joint& j, const JointLambdas& L, const State& state, Real inv_h2) {
  const int n = direct_rows(j);
  JointRows rows;
  rows.c.setZero(n);
  rows.alpha_tilde.setConstant(n, j.compliance * inv_h2);
  rows.lambda.setZero(n);
  for (auto& jac : rows.jacobian) jac.setZero(n, 6);
  const ConstEndView a = const_end_view(state, j.ends[0]), b = const_end_view(state, j.ends[1]);
  switch (j.type) {
    case JointType::spherical:
      attachment_rows(a, b, rows, 0);
      rows.lambda = L.position;
      break;
    case JointType::fixed:
      attachment_rows(a, b, rows, 0);
      orientation_rows(a, b, rows, 3);
      rows.alpha_tilde.tail<3>().setConstant(j.angular_compliance * inv_h2);
      rows.lambda << L.position, L.orientation;
      break;
    case JointType::hinge:
      attachment_rows(a, b, rows, 0);
      alignment_rows(a, b, rows, 3);
      rows.alpha_tilde.tail<2>().setConstant(j.angular_compliance * inv_h2);
      rows.lambda << L.position, L.orientation.head<2>();
      break;
    case JointType::distance:
      distance_row(a, b, j.lower, rows);
      rows.lambda(0) = L.distance;
      break;
    case JointType::prismatic: break;
  }
  return rows;
}

void add_to_lambdas(const Joint& j, const Column& d, JointLambdas& L) {
  switch (j.type) {
    case JointType::spherical: L.position += d.head<3>(); break;
    case JointType::fixed:
      L.position += d.head<3>();
      L.orientation += d.tail<3>();
      break;
    case JointType::hinge:
      L.position += d.head<3>();
      L.orientation.head<2>() += d.tail<2>();
      break;
    case JointType::distance: L.distance += d(0); break;
    case JointType::prismatic: break;
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

int direct_rows(const Joint& joint) {
  switch (joint.type) {
    case JointType::spherical: return 3;
    case JointType::fixed: return 6;
    case JointType::hinge: return 5;
    case JointType::distance: return joint.lower == joint.upper ? 1 : 0;
    case JointType::prismatic: return 0;
  }
  return 0;
}

JointForest build_joint_forest(const RigidBodyModel& bodies, const std::vector<Joint>& joints) {
  JointForest forest;
  forest.joint_in_tree.assign(joints.size(), 0);
  Components components(bodies.count());
  std::vector<std::vector<Index>> body_joints(bodies.count());
  for (size_t k = 0; k < joints.size(); ++k) {
    const Joint& j = joints[k];
    if (direct_rows(j) == 0) continue;
    if (j.ends[0].kind == JointEndKind::particle || j.ends[1].kind == JointEndKind::particle) continue;
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
  for (Index i = 0; i < n; ++i) {
    JointTreeNode node = order[n - 1 - i];
    if (node.parent >= 0) node.parent = n - 1 - node.parent;
    forest.nodes[i] = node;
  }
  return forest;
}

namespace {

// One linearised solve (a Newton step on every tree joint's equality rows), skipped when the largest
// |C + alpha~ lambda| is already below the tolerance; returns whether it solved.
bool direct_pass(const Model& model, State& state, Real inv_h2) {
  const JointForest& forest = model.joint_forest;
  const size_t n = forest.nodes.size();
  Real residual = 0;

  // Diagonal blocks H_ii (M for a body, -alpha~ for a joint) and right-hand sides b_i.
  std::vector<JointRows> rows(n);
  std::vector<Block> diagonal(n), to_parent(n);
  std::vector<Column> s(n);
  for (size_t i = 0; i < n; ++i) {
    const JointTreeNode& node = forest.nodes[i];
    if (node.is_body) {
      const Index b = node.index;
      const Mat3 R = state.rigid.orientation[b].toRotationMatrix();
      diagonal[i].setZero(6, 6);
      diagonal[i].topLeftCorner<3, 3>() = model.rigid.body_mass[b] * Mat3::Identity();
      diagonal[i].bottomRightCorner<3, 3>() = R * model.rigid.body_inertia[b].asDiagonal() * R.transpose();
      s[i].setZero(6);
    } else {
      const Joint& j = model.joints[node.index];
      rows[i] = joint_rows(j, state.joint_lambda[node.index], state, inv_h2);
      diagonal[i] = -Block(rows[i].alpha_tilde.asDiagonal());
      s[i] = rows[i].c + rows[i].alpha_tilde.cwiseProduct(rows[i].lambda);
      residual = std::max(residual, s[i].cwiseAbs().maxCoeff());
    }
  }
  if (residual <= kDirectTolerance) return false;
  // Off-diagonal H_i,parent = -J (rows x 6) below a body, -J^T (6 x rows) below a joint.
  auto coupling = [&](size_t i) -> Block {
    const JointTreeNode& node = forest.nodes[i];
    const size_t joint_node = node.is_body ? node.parent : i;
    const Index body = node.is_body ? node.index : forest.nodes[node.parent].index;
    const Joint& j = model.joints[forest.nodes[joint_node].index];
    const int slot = j.ends[0].kind == JointEndKind::body && j.ends[0].index == body ? 0 : 1;
    const RowJacobian& jac = rows[joint_node].jacobian[slot];
    return node.is_body ? Block(-jac.transpose()) : Block(-jac);
  };

  // Factor, leaves first: D_i -> LDL^T, J_i = D_i^-1 H_i,parent, D_parent -= H_i,parent^T J_i.
  std::vector<Eigen::LDLT<Block>> factor(n);
  for (size_t i = 0; i < n; ++i) {
    factor[i].compute(diagonal[i]);
    const Index p = forest.nodes[i].parent;
    if (p < 0) continue;
    const Block h_ip = coupling(i);
    to_parent[i] = factor[i].solve(h_ip);
    diagonal[p] -= h_ip.transpose() * to_parent[i];
  }
  // Forward (leaves to roots), then backward (roots to leaves).
  for (size_t i = 0; i < n; ++i)
    if (const Index p = forest.nodes[i].parent; p >= 0) s[p] -= to_parent[i].transpose() * s[i];
  for (size_t i = n; i-- > 0;) {
    s[i] = factor[i].solve(s[i]);
    if (const Index p = forest.nodes[i].parent; p >= 0) s[i] -= to_parent[i] * s[p];
  }

  for (size_t i = 0; i < n; ++i) {
    const JointTreeNode& node = forest.nodes[i];
    if (node.is_body) {
      const BodyHandle body = rigid_body_handle(model.rigid, state.rigid, node.index);
      *body.position += s[i].head<3>();
      body.rotate_by(s[i].tail<3>());
    } else {
      add_to_lambdas(model.joints[node.index], s[i], state.joint_lambda[node.index]);
    }
  }
  return true;
}

}  // namespace

int solve_joint_forest(const Model& model, State& state, Real h) {
  if (model.joint_forest.empty()) return 0;
  const Real inv_h2 = 1 / (h * h);
  int passes = 0;
  while (passes < kMaxDirectPasses && direct_pass(model, state, inv_h2)) ++passes;
  return passes;
}

}  // namespace moreau
