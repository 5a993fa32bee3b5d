#include "moreau/rigid/tree_contacts.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Cholesky>

#include "moreau/collision/particle_body_contacts.hpp"
#include "moreau/constraints/contact_rows.hpp"
#include "moreau/model/model.hpp"
#include "moreau/model/state.hpp"
#include "moreau/rigid/body_handle.hpp"

namespace moreau {

namespace {

bool comes_within(const RigidManifold& mf, const RigidContacts& contacts, const RigidBodyState& s, Real gap) {
  const Pose pa{s.position[mf.body_a], s.orientation[mf.body_a]}, pb{s.position[mf.body_b], s.orientation[mf.body_b]};
  for (Index i = mf.first; i < mf.first + mf.count; ++i)
    if (contact_point_at_poses(mf.frame, contacts.points[i].geometry, pa, pb).separation < gap) return true;
  return false;
}

}  // namespace

void choose_tree_contacts(const Model& model, State& state) {
  const JointForest& forest = model.joint_forest;
  RigidContacts& contacts = state.rigid_contacts;
  if (forest.empty()) return;  // no manifold is ever marked
  std::vector<char> shared = forest.tree_has_loose_joints;  // per root node
  auto share = [&](Index body) {
    if (const Index tree = forest.tree_of_body(body); tree >= 0) shared[tree] = 1;
  };
  for (const auto& [body, particle] : state.particle_body_contacts.pair) share(body);
  // Contacts with a dynamic body outside the forest share the tree; then contacts between trees
  // pass it on, until nothing changes.
  std::vector<const RigidManifold*> between_trees;
  for (const RigidManifold& mf : contacts.manifolds) {
    if (!model.rigid.is_dynamic(mf.body_a) || !model.rigid.is_dynamic(mf.body_b)) continue;
    const bool tree_a = forest.tree_of_body(mf.body_a) >= 0, tree_b = forest.tree_of_body(mf.body_b) >= 0;
    if (!tree_a && !tree_b) continue;
    if (!comes_within(mf, contacts, state.rigid, kSharingGap)) continue;
    if (tree_a && tree_b) {
      between_trees.push_back(&mf);
    } else {
      share(mf.body_a);
      share(mf.body_b);
    }
  }
  for (bool changed = true; changed;) {
    changed = false;
    for (const RigidManifold* mf : between_trees) {
      const Index ta = forest.tree_of_body(mf->body_a), tb = forest.tree_of_body(mf->body_b);
      if (shared[ta] != shared[tb]) {
        shared[ta] = shared[tb] = 1;
        changed = true;
      }
    }
  }
  for (RigidManifold& mf : contacts.manifolds) {
    const Index ta = forest.tree_of_body(mf.body_a), tb = forest.tree_of_body(mf.body_b);
    if (ta >= 0 && tb >= 0) {
      mf.with_joints = !shared[ta] && !shared[tb];
    } else if (ta >= 0 || tb >= 0) {
      const Index other = ta >= 0 ? mf.body_b : mf.body_a;
      mf.with_joints = !model.rigid.is_dynamic(other) && !shared[ta >= 0 ? ta : tb];
    } else {
      mf.with_joints = false;
    }
  }
}

TreeContacts::TreeContacts(const Model& model, State& state, const SubstepStart& start) {
  const JointForest& forest = model.joint_forest;
  RigidContacts& contacts = state.rigid_contacts;
  for (size_t m = 0; m < contacts.manifolds.size(); ++m) {
    const RigidManifold& mf = contacts.manifolds[m];
    if (!mf.with_joints) continue;
    RigidContactPoint* points = contacts.points.data() + mf.first;
    const ContactRows rows = manifold_rows(mf, points, state.rigid, start, ContactPoints::all);
    const std::array<Index, 2> node{forest.node_of_body(mf.body_a), forest.node_of_body(mf.body_b)};
    // Zero weight for a body that is not dynamic (the only other kind a tree manifold has).
    const BodyHandle ha = rigid_body_handle(model.rigid, state.rigid, mf.body_a);
    const BodyHandle hb = rigid_body_handle(model.rigid, state.rigid, mf.body_b);
    // Judged sliding earlier in this substep (touching is cleared at its start): it stays so.
    const bool may_stick = mf.static_friction > 0 && !(mf.touching && mf.sliding);
    for (int j = 0; j < rows.points; ++j) {
      const RigidContactPoint& c = points[rows.point[j]];
      if (rows.C[3 * j] >= 0 && c.lambda_normal <= 0) continue;  // apart and not pushing: no rows
      TreeContactPoint p;
      p.manifold = static_cast<Index>(m);
      p.point = rows.point[j];
      p.node = node;
      p.static_friction = mf.static_friction;
      p.lambda = Vec3(c.lambda_normal, c.lambda_tangent.x(), c.lambda_tangent.y());
      BodyRows point_rows = BodyRows::zero(rows.end, 3, 0);
      for (int r = 0; r < 3; ++r) {
        const int row = 3 * j + r;
        const Vec3& d = rows.direction[row];
        point_rows.set_point_row(r, d, rows.offset_a[row], rows.offset_b[row]);
        p.C[r] = rows.C[row];
        p.alpha_tilde[r] = kContactRegularization * (ha.positional_weight(rows.offset_a[row], d) +
                                                     hb.positional_weight(rows.offset_b[row], d));
      }
      p.G = point_rows.jacobian;
      p.active = true;
      p.sticking = may_stick;
      points_.push_back(p);
    }
  }
  link_dlambda_.assign(points_.size(), Vec3::Zero());
}

Real TreeContacts::residual() const {
  Real largest = 0;
  for (const TreeContactPoint& p : points_)
    for (int r = 0; r < p.solved_rows(); ++r)
      largest = std::max(largest, std::abs(p.C[r] + p.alpha_tilde[r] * p.lambda[r]));
  return largest;
}

void TreeContacts::add_to(std::vector<TreeBlock>& diagonal, std::vector<TreeColumn>& rhs) const {
  for (const TreeContactPoint& p : points_) {
    const int solved = p.solved_rows();
    for (int e = 0; e < 2; ++e) {
      if (p.node[e] < 0) continue;
      for (int r = 0; r < 3; ++r) {
        const auto g = p.G[e].row(r).transpose();
        if (r >= solved) {
          if (p.lambda[r] != 0) rhs[p.node[e]] -= g * p.lambda[r];  // released: dlambda = -lambda
        } else if (!p.is_link()) {
          diagonal[p.node[e]] += g * g.transpose() / p.alpha_tilde[r];
          rhs[p.node[e]] -= g * ((p.C[r] + p.alpha_tilde[r] * p.lambda[r]) / p.alpha_tilde[r]);
        }
      }
    }
  }
}

void TreeContacts::solve_links(const TreeFactorization& tree, std::vector<TreeColumn>& solution) {
  // The solved link rows, each a column of Y = A^-1 G^T.
  struct LinkRow {
    size_t point;
    int row;
  };
  std::vector<LinkRow> link_rows;
  for (size_t k = 0; k < points_.size(); ++k)
    if (points_[k].is_link())
      for (int r = 0; r < points_[k].solved_rows(); ++r) link_rows.push_back({k, r});
  for (size_t k = 0; k < points_.size(); ++k) link_dlambda_[k] = -points_[k].lambda;  // released rows
  const int m = static_cast<int>(link_rows.size());
  if (m == 0) return;
  const size_t n = solution.size();
  std::vector<std::vector<TreeColumn>> Y(m);
  for (int q = 0; q < m; ++q) {
    const TreeContactPoint& p = points_[link_rows[q].point];
    std::vector<TreeColumn>& y = Y[q];
    y.resize(n);
    for (size_t i = 0; i < n; ++i) y[i].setZero(solution[i].size());
    for (int e = 0; e < 2; ++e) y[p.node[e]] += p.G[e].row(link_rows[q].row).transpose();
    tree.solve(y);
  }
  // G applied to a node-indexed vector, for link row q.
  auto row_of = [&](int q, const std::vector<TreeColumn>& v) {
    const TreeContactPoint& p = points_[link_rows[q].point];
    Real value = 0;
    for (int e = 0; e < 2; ++e) value += p.G[e].row(link_rows[q].row).dot(v[p.node[e]].head<6>());
    return value;
  };
  Eigen::MatrixXd S(m, m);
  Eigen::VectorXd rhs(m);
  for (int q = 0; q < m; ++q) {
    const TreeContactPoint& p = points_[link_rows[q].point];
    const int r = link_rows[q].row;
    for (int c = 0; c < m; ++c) S(q, c) = row_of(q, Y[c]);
    S(q, q) += p.alpha_tilde[r];
    rhs[q] = -(p.C[r] + p.alpha_tilde[r] * p.lambda[r] + row_of(q, solution));
  }
  // S is symmetric in exact arithmetic; its two triangles differ by rounding.
  const Eigen::MatrixXd symmetric = (S + S.transpose()) / 2;
  const Eigen::VectorXd dlambda = symmetric.ldlt().solve(rhs);
  for (int q = 0; q < m; ++q) {
    link_dlambda_[link_rows[q].point][link_rows[q].row] = dlambda[q];
    for (size_t i = 0; i < n; ++i) solution[i] += dlambda[q] * Y[q][i];
  }
}

Vec3 TreeContacts::dlambda(size_t k, const std::vector<TreeColumn>& solution) const {
  const TreeContactPoint& p = points_[k];
  if (p.is_link()) return link_dlambda_[k];
  const int e = p.node[0] >= 0 ? 0 : 1;
  const TreeColumn& y = solution[p.node[e]];
  Vec3 d = -p.lambda;
  for (int r = 0; r < p.solved_rows(); ++r)
    d[r] = -(p.C[r] + p.alpha_tilde[r] * p.lambda[r] + p.G[e].row(r).dot(y.head<6>())) / p.alpha_tilde[r];
  return d;
}

bool TreeContacts::holds(const std::vector<TreeColumn>& solution) {
  bool holds = true;
  for (size_t k = 0; k < points_.size(); ++k) {
    TreeContactPoint& p = points_[k];
    if (!p.active) continue;
    const Vec3 total = p.lambda + dlambda(k, solution);
    if (total[0] < 0) {
      p.active = p.sticking = false;
      holds = false;
    } else if (p.sticking && total.tail<2>().norm() > (1 + 1e-9) * p.static_friction * total[0]) {
      p.sticking = false;
      holds = false;
    }
  }
  return holds;
}

void TreeContacts::accept(const std::vector<TreeColumn>& solution, State& state) const {
  RigidContacts& contacts = state.rigid_contacts;
  // A manifold slides once a pushing point has lost its static friction, and keeps sliding for
  // the rest of the substep (TreeContacts' constructor): re-judged at every pass, a sliding point
  // would start each pass stuck and be released again, and the passes would not settle. (Gauss-Seidel
  // judges a manifold as a whole, sliding when every pushing point is on its cone.)
  for (const TreeContactPoint& p : points_) {
    contacts.manifolds[p.manifold].touching = false;
    contacts.manifolds[p.manifold].sliding = false;
  }
  for (size_t k = 0; k < points_.size(); ++k) {
    const TreeContactPoint& p = points_[k];
    RigidManifold& mf = contacts.manifolds[p.manifold];
    RigidContactPoint& c = contacts.points[mf.first + p.point];
    Vec3 total = p.lambda + dlambda(k, solution);
    // Left outside its set when the active set ran out of solves: kept to a push inside its cone.
    total[0] = std::max(total[0], Real(0));
    if (const Real t = total.tail<2>().norm(); t > p.static_friction * total[0])
      total.tail<2>() *= t > 0 ? p.static_friction * total[0] / t : 0;
    c.lambda_normal = total[0];
    c.lambda_tangent = total.tail<2>();
    c.touching = total[0] > 0;
    mf.touching |= c.touching;
    mf.sliding |= c.touching && !p.sticking && p.static_friction > 0;
  }
}

}  // namespace moreau
