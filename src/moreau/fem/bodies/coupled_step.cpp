#include "moreau/fem/bodies/coupled_step.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "moreau/fem/solids/fem_assembly.hpp"
#include "moreau/fem/core/newton.hpp"
#include "moreau/fem/solids/static_solver.hpp"

namespace moreau {

namespace {

using Triplets = std::vector<Eigen::Triplet<Real, int>>;

// Where the unknowns live: the solids' free dofs, then per body q (12) and its internal
// multipliers (6), then the joints' multipliers in joint order.
struct Layout {
  Index free = 0, bodies = 0, joint_rows = 0;
  Index body(Index b) const { return free + 18 * b; }
  Index joints() const { return free + 18 * bodies; }
  Index size() const { return joints() + joint_rows; }
};

// The configuration during Newton: solids' u1 (all dofs), bodies' q1.
struct Configuration {
  VectorX u;
  std::vector<DirectorVector> q;
};

Vec3 end_position(const FemProblem& p, const FemJointEnd& e, const Configuration& c) {
  switch (e.kind) {
    case FemJointEndKind::world: return e.coordinates;
    case FemJointEndKind::body: {
      const DirectorVector& q = c.q[e.index];
      Vec3 x = q.head<3>();
      for (int i = 0; i < 3; ++i) x += e.coordinates[i] * q.segment<3>(3 + 3 * i);
      return x;
    }
    case FemJointEndKind::node: return p.model.reference_position(e.index) + c.u.segment<3>(3 * e.index);
  }
  return Vec3::Zero();
}

Vec3 end_direction(const FemJointEnd& e, const Vec3& direction, const Configuration& c) {
  if (e.kind != FemJointEndKind::body) return direction;
  const DirectorVector& q = c.q[e.index];
  Vec3 n = Vec3::Zero();
  for (int i = 0; i < 3; ++i) n += direction[i] * q.segment<3>(3 + 3 * i);
  return n;
}

// The rows of all joints at a configuration: values g and, per row, the gradient as (unknown,
// value) pairs.
struct JointRows {
  VectorX g;
  std::vector<std::vector<std::pair<Index, Real>>> gradient;
};

JointRows evaluate_joints(const FemProblem& p, const Layout& layout, const Configuration& c) {
  JointRows rows;
  rows.g.resize(layout.joint_rows);
  rows.gradient.assign(layout.joint_rows, {});
  Index r = 0;
  for (const FemJoint& joint : p.joints)
    for (const FemJointRows& group : joint.rows) {
      if (group.kind == FemJointRows::Kind::coincide) {
        const Vec3 g = end_position(p, group.a, c) - end_position(p, group.b, c);
        for (int k = 0; k < 3; ++k) rows.g[r + k] = g[k];
        // Gradients: bodies (phi and directors, component k), nodes (their free dof k).
        for (const auto& [end, sign] : {std::pair<const FemJointEnd*, Real>{&group.a, 1.0}, {&group.b, -1.0}}) {
          if (end->kind == FemJointEndKind::body) {
            for (int k = 0; k < 3; ++k) {
              rows.gradient[r + k].push_back({layout.body(end->index) + k, sign});
              for (int i = 0; i < 3; ++i)
                rows.gradient[r + k].push_back({layout.body(end->index) + 3 + 3 * i + k, sign * end->coordinates[i]});
            }
          } else if (end->kind == FemJointEndKind::node) {
            for (int k = 0; k < 3; ++k) {
              const Index f = p.model.free_index[p.model.dof(end->index, k)];
              if (f >= 0) rows.gradient[r + k].push_back({f, sign});
            }
          }
        }
        r += 3;
      } else {
        const Vec3 na = end_direction(group.a, group.direction_a, c), eb = end_direction(group.b, group.direction_b, c);
        rows.g[r] = na.dot(eb);
        // d(na . eb)/d d_i^A = alpha_i eb, d/d d_i^B = beta_i na.
        for (const auto& [end, direction, other] :
             {std::tuple<const FemJointEnd*, Vec3, Vec3>{&group.a, group.direction_a, eb}, {&group.b, group.direction_b, na}}) {
          if (end->kind != FemJointEndKind::body) continue;
          for (int i = 0; i < 3; ++i)
            for (int k = 0; k < 3; ++k)
              rows.gradient[r].push_back({layout.body(end->index) + 3 + 3 * i + k, direction[i] * other[k]});
        }
        r += 1;
      }
    }
  return rows;
}

}  // namespace

Real joint_violation(const FemProblem& problem, const FemRunState& run, const FemJoint& joint) {
  Configuration c{run.solids.u, {}};
  for (const DirectorState& s : run.bodies) c.q.push_back(director_configuration(s));
  Real worst = 0;
  for (const FemJointRows& group : joint.rows) {
    if (group.kind == FemJointRows::Kind::coincide) {
      worst = std::max(worst, (end_position(problem, group.a, c) - end_position(problem, group.b, c)).norm());
    } else {
      worst = std::max(worst, std::abs(end_direction(group.a, group.direction_a, c).dot(end_direction(group.b, group.direction_b, c))));
    }
  }
  return worst;
}

namespace {

// One iterate of the coupled step: the configuration, the multipliers, and what is evaluated there.
struct CoupledIterate {
  Configuration z;
  VectorX lambda;  // internal (6 per body), then joints
  VectorX f;       // the solids' algorithmic internal forces
  SparseMatrix K;  // and their tangent
  InternalForceResult cells;
  JointRows rows1, rows_mid;  // joint rows at z_1 and at the midpoint
  std::vector<DirectorStepRows> body_rows;
  VectorX R;
};

// The coupled step's residual (coupled_step.hpp) and Jacobian for the Newton driver. Unknowns:
// the layout's; the merit is |R_momentum| / force scale + |R_constraints|.
class CoupledStepSystem final : public NewtonIterates<CoupledIterate> {
 public:
  CoupledStepSystem(const FemProblem& problem, const SparseMatrix& mass, StepRule rule, Real h, const FemRunState& run,
                    SparseLuSolver& solver, const NewtonSettings& settings, NewtonResult& result)
      : problem_(problem), model_(problem.model), mass_(mass), rule_(rule), h_(h), s0_(run.solids), solver_(solver),
        settings_(settings), result_(result) {
    layout_.free = model_.free_count;
    layout_.bodies = static_cast<Index>(problem.rigid_bodies.size());
    for (const FemJoint& j : problem.joints) layout_.joint_rows += j.row_count();
    const Real t_mid = s0_.time + 0.5 * h;
    if (model_.dof_count() > 0) f_ext_ = external_forces(model_, t_mid);
    for (Index b = 0; b < layout_.bodies; ++b) {
      q0_.push_back(director_configuration(run.bodies[b]));
      v0_.push_back(director_velocities(run.bodies[b]));
    }
    // Predictor; multipliers start at zero.
    now_.z = {dynamic_step_predictor(model_, s0_.u, s0_.v, h), {}};
    apply_prescribed(model_, s0_.time + h, now_.z.u);
    for (Index b = 0; b < layout_.bodies; ++b) now_.z.q.push_back(q0_[b] + h * v0_[b]);
    now_.lambda = VectorX::Zero(6 * layout_.bodies + layout_.joint_rows);
    assemble(now_);
  }

  NewtonEvaluation evaluate(const VectorX* dz, Real alpha) override {
    if (!dz) return measure(now_);
    trial_.z = now_.z;
    trial_.lambda = now_.lambda;
    if (model_.dof_count() > 0) add_free_part(model_, alpha * dz->head(layout_.free), trial_.z.u);
    for (Index b = 0; b < layout_.bodies; ++b) {
      trial_.z.q[b] += alpha * dz->segment<12>(layout_.body(b));
      trial_.lambda.segment<6>(6 * b) += alpha * dz->segment<6>(layout_.body(b) + 12);
    }
    if (layout_.joint_rows > 0) trial_.lambda.tail(layout_.joint_rows) += alpha * dz->tail(layout_.joint_rows);
    assemble(trial_);
    return measure(trial_);
  }

  bool solve(VectorX& dz, std::string& failure) override;

  // |alpha dz| of the configuration against the step's motion (as in step_dynamic).
  Real relative_correction(const VectorX& dz, Real alpha) const override {
    Real correction = 0, motion = 0;
    if (model_.dof_count() > 0) {
      correction += (alpha * dz.head(layout_.free)).squaredNorm();
      motion += free_part(model_, now_.z.u - s0_.u).squaredNorm();
    }
    for (Index b = 0; b < layout_.bodies; ++b) {
      correction += (alpha * dz.segment<12>(layout_.body(b))).squaredNorm();
      motion += (now_.z.q[b] - q0_[b]).squaredNorm();
    }
    return std::sqrt(correction / std::max(motion, Real(1e-300)));
  }

  // Accepts the converged step: velocities by the midpoint relation (prescribed dofs: the
  // derivative of their values).
  void finish(FemRunState& run) const {
    if (model_.dof_count() > 0) {
      FemDynamicState& s = run.solids;
      const VectorX u0 = s.u;
      s.v = (2 / h_) * (now_.z.u - u0) - s.v;
      apply_prescribed_velocity(model_, s.time + h_, s.v);
      s.u = now_.z.u;
      s.energy = now_.cells.energy;
    }
    run.solids.time += h_;
    for (Index b = 0; b < layout_.bodies; ++b) set_director_step(q0_[b], v0_[b], now_.z.q[b], h_, run.bodies[b]);
  }

 private:
  void assemble(CoupledIterate& it) {
    if (model_.dof_count() == 0) {
      it.cells = {};
      return;
    }
    it.cells = timed(result_.assembly_s, [&] {
      return assemble_step_forces(model_, s0_.u, it.z.u, rule_, it.f, &it.K, settings_.threads);
    });
  }

  NewtonEvaluation measure(CoupledIterate& it) const;

  const FemProblem& problem_;
  const FemModel& model_;
  const SparseMatrix& mass_;
  StepRule rule_;
  Real h_;
  const FemDynamicState& s0_;
  SparseLuSolver& solver_;
  const NewtonSettings& settings_;
  NewtonResult& result_;
  Layout layout_;
  VectorX f_ext_;
  std::vector<DirectorVector> q0_, v0_;
  Triplets triplets_;
};

NewtonEvaluation CoupledStepSystem::measure(CoupledIterate& it) const {
  NewtonEvaluation e;
  e.valid = it.cells.valid;
  if (!e.valid) {
    e.invalid = fmt::format("cell {} of '{}'", it.cells.invalid_cell, it.cells.invalid_solid);
    return e;
  }
  const Index n = layout_.size();
  const Real c = 2 / (h_ * h_);
  Configuration mid{0.5 * (s0_.u + it.z.u), {}};
  for (Index b = 0; b < layout_.bodies; ++b) mid.q.push_back(0.5 * (q0_[b] + it.z.q[b]));
  it.rows1 = evaluate_joints(problem_, layout_, it.z);
  it.rows_mid = evaluate_joints(problem_, layout_, mid);
  it.R.resize(n);
  Real force_scale = 1e-300;
  if (model_.dof_count() > 0) {
    const VectorX inertia = mass_times(model_, c * (it.z.u - s0_.u) - (2 / h_) * s0_.v);
    it.R.head(layout_.free) = free_part(model_, inertia + it.f - f_ext_);
    force_scale = std::max({force_scale, inertia.norm(), it.f.norm(), f_ext_.norm()});
  }
  it.body_rows.clear();
  for (Index b = 0; b < layout_.bodies; ++b) {
    const DirectorBody& body = problem_.rigid_bodies[b].body;
    it.body_rows.push_back(director_step_rows(body, q0_[b], v0_[b], h_, body.mass * problem_.gravity, Vec3::Zero(), it.z.q[b],
                                              it.lambda.segment<6>(6 * b), true));
    it.R.segment<18>(layout_.body(b)) = it.body_rows.back().residual;
    force_scale = std::max(force_scale, it.body_rows.back().force_scale);
  }
  // Joint forces J(z_mid)^T lambda_j on the momentum rows; joint rows g(z1).
  for (Index r = 0; r < layout_.joint_rows; ++r) {
    for (const auto& [unknown, value] : it.rows_mid.gradient[r]) it.R[unknown] += value * it.lambda[6 * layout_.bodies + r];
    it.R[layout_.joints() + r] = it.rows1.g[r];
  }
  Real momentum_norm = 0, constraint_norm = 0;
  for (Index i = 0; i < n; ++i) {
    const bool constraint_row = i >= layout_.joints() || (i >= layout_.free && (i - layout_.free) % 18 >= 12);
    (constraint_row ? constraint_norm : momentum_norm) += it.R[i] * it.R[i];
  }
  momentum_norm = std::sqrt(momentum_norm);
  constraint_norm = std::sqrt(constraint_norm);
  e.norm = momentum_norm / force_scale + constraint_norm;
  e.converged = momentum_norm <= settings_.tolerance * force_scale && constraint_norm <= settings_.tolerance;
  e.relative = std::max(momentum_norm / force_scale, constraint_norm);
  e.describe = fmt::format("force residual {:.3e} of {:.3e}, constraint residual {:.3e}", momentum_norm, force_scale,
                           constraint_norm);
  return e;
}

bool CoupledStepSystem::solve(VectorX& dz, std::string& failure) {
  const Index n = layout_.size();
  const Real c = 2 / (h_ * h_);
  const CoupledIterate& it = now_;
  Triplets& triplets = triplets_;
  triplets.clear();
  if (model_.dof_count() > 0) {
    for (int col = 0; col < it.K.outerSize(); ++col)
      for (SparseMatrix::InnerIterator k(it.K, col); k; ++k) triplets.emplace_back(k.row(), col, k.value());
    for (int col = 0; col < mass_.outerSize(); ++col)
      for (SparseMatrix::InnerIterator k(mass_, col); k; ++k) triplets.emplace_back(k.row(), col, c * k.value());
  }
  // Every entry of a body's 18 x 18 block is inserted, zero or not: the sparsity must not change
  // between iterations, since UMFPACK's symbolic analysis is reused.
  for (Index b = 0; b < layout_.bodies; ++b)
    for (int i = 0; i < 18; ++i)
      for (int j = 0; j < 18; ++j) triplets.emplace_back(layout_.body(b) + i, layout_.body(b) + j, it.body_rows[b].jacobian(i, j));
  Index r = 0;
  for (const FemJoint& joint : problem_.joints)
    for (const FemJointRows& group : joint.rows) {
      const int count = group.kind == FemJointRows::Kind::coincide ? 3 : 1;
      for (int k = 0; k < count; ++k, ++r) {
        for (const auto& [unknown, value] : it.rows_mid.gradient[r]) triplets.emplace_back(unknown, layout_.joints() + r, value);
        for (const auto& [unknown, value] : it.rows1.gradient[r]) triplets.emplace_back(layout_.joints() + r, unknown, value);
      }
      // Axis rows are quadratic: the transpose term J(z_mid)^T lambda has the derivative
      // lambda/2 * alpha_i beta_j I between the directors of the two ends.
      if (group.kind == FemJointRows::Kind::perpendicular && group.a.kind == FemJointEndKind::body &&
          group.b.kind == FemJointEndKind::body) {
        const Real l = 0.5 * it.lambda[6 * layout_.bodies + r - 1];
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j)
            for (int k = 0; k < 3; ++k) {
              const Real v = l * group.direction_a[i] * group.direction_b[j];
              triplets.emplace_back(layout_.body(group.a.index) + 3 + 3 * i + k, layout_.body(group.b.index) + 3 + 3 * j + k, v);
              triplets.emplace_back(layout_.body(group.b.index) + 3 + 3 * j + k, layout_.body(group.a.index) + 3 + 3 * i + k, v);
            }
      }
    }
  SparseMatrix A(n, n);
  A.setFromTriplets(triplets.begin(), triplets.end());
  A.makeCompressed();
  if (!timed(result_.solve_s, [&] { return solver_.factorize(A); })) {
    failure = "the coupled step's Jacobian is singular (a joint repeated, or a body held twice?)";
    return false;
  }
  const VectorX rhs = -it.R;
  dz = timed(result_.solve_s, [&] { return solver_.solve(rhs); });
  return true;
}

}  // namespace

NewtonResult step_coupled(const FemProblem& problem, const SparseMatrix& mass, StepRule rule, Real h, FemRunState& run,
                          SparseLuSolver& solver, const NewtonSettings& settings) {
  NewtonResult result;
  CoupledStepSystem system(problem, mass, rule, h, run, solver, settings, result);
  if (!newton_solve(system, settings, "the coupled step", result)) return result;
  system.finish(run);
  result.converged = true;
  return result;
}

}  // namespace moreau
