#include "moreau/fem/bodies/coupled_step.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "moreau/fem/solids/fem_assembly.hpp"
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

NewtonResult step_coupled(const FemProblem& problem, const SparseMatrix& mass, StepRule rule, Real h, FemRunState& run,
                          SparseLuSolver& solver, const NewtonSettings& settings) {
  const FemModel& model = problem.model;
  NewtonResult result;
  Layout layout;
  layout.free = model.free_count;
  layout.bodies = static_cast<Index>(problem.rigid_bodies.size());
  for (const FemJoint& j : problem.joints) layout.joint_rows += j.row_count();
  const Index n = layout.size();

  const FemDynamicState& s0 = run.solids;
  const Real t_mid = s0.time + 0.5 * h, c = 2 / (h * h);
  const VectorX f_ext = model.dof_count() > 0 ? external_forces(model, t_mid) : VectorX();
  std::vector<DirectorVector> q0, v0;
  for (Index b = 0; b < layout.bodies; ++b) {
    q0.push_back(director_configuration(run.bodies[b]));
    v0.push_back(director_velocities(run.bodies[b]));
  }
  // Predictor; multipliers start at zero.
  Configuration z{dynamic_step_predictor(model, s0.u, s0.v, h), {}};
  apply_prescribed(model, s0.time + h, z.u);
  for (Index b = 0; b < layout.bodies; ++b) z.q.push_back(q0[b] + h * v0[b]);
  VectorX lambda = VectorX::Zero(6 * layout.bodies + layout.joint_rows);  // internal (6 per body), then joints
  auto internal = [&](Index b) { return lambda.segment<6>(6 * b); };
  auto joint_lambda = [&]() { return lambda.tail(layout.joint_rows); };

  VectorX f;
  SparseMatrix K;
  InternalForceResult cells{};
  auto assemble_solids = [&](const Configuration& cfg, bool tangent) {
    if (model.dof_count() == 0) return InternalForceResult{};
    return timed(result.assembly_s, [&] { return assemble_step_forces(model, s0.u, cfg.u, rule, f, tangent ? &K : nullptr, settings.threads); });
  };
  cells = assemble_solids(z, true);
  if (!cells.valid) {
    result.failure = fmt::format("cell {} of '{}' is inverted at the start of the step", cells.invalid_cell, cells.invalid_solid);
    return result;
  }
  VectorX R(n);
  Triplets triplets;
  Real last_correction = std::numeric_limits<Real>::infinity();  // |correction| / |motion| of the last step
  for (;;) {
    // Residuals.
    Configuration mid{0.5 * (s0.u + z.u), {}};
    for (Index b = 0; b < layout.bodies; ++b) mid.q.push_back(0.5 * (q0[b] + z.q[b]));
    const JointRows rows1 = evaluate_joints(problem, layout, z), rows_mid = evaluate_joints(problem, layout, mid);
    Real force_scale = 1e-300;
    if (model.dof_count() > 0) {
      const VectorX inertia = mass_times(model, c * (z.u - s0.u) - (2 / h) * s0.v);
      R.head(layout.free) = free_part(model, inertia + f - f_ext);
      force_scale = std::max({force_scale, inertia.norm(), f.norm(), f_ext.norm()});
    }
    std::vector<DirectorStepRows> body_rows;
    for (Index b = 0; b < layout.bodies; ++b) {
      const DirectorBody& body = problem.rigid_bodies[b].body;
      body_rows.push_back(
          director_step_rows(body, q0[b], v0[b], h, body.mass * problem.gravity, Vec3::Zero(), z.q[b], internal(b), true));
      R.segment<18>(layout.body(b)) = body_rows.back().residual;
      force_scale = std::max(force_scale, body_rows.back().force_scale);
    }
    // Joint forces J(z_mid)^T lambda_j on the momentum rows; joint rows g(z1).
    for (Index r = 0; r < layout.joint_rows; ++r) {
      for (const auto& [unknown, value] : rows_mid.gradient[r]) R[unknown] += value * joint_lambda()[r];
      R[layout.joints() + r] = rows1.g[r];
    }
    Real momentum_norm = 0, constraint_norm = 0;
    for (Index i = 0; i < n; ++i) {
      const bool constraint_row = i >= layout.joints() || (i >= layout.free && (i - layout.free) % 18 >= 12);
      (constraint_row ? constraint_norm : momentum_norm) += R[i] * R[i];
    }
    momentum_norm = std::sqrt(momentum_norm);
    constraint_norm = std::sqrt(constraint_norm);
    result.residual_norms.push_back(momentum_norm / force_scale + constraint_norm);
    if (momentum_norm <= settings.tolerance * force_scale && constraint_norm <= settings.tolerance) break;
    if (result.iterations == settings.max_iterations) {
      result.failure = fmt::format("the coupled step did not converge in {} Newton iterations (force residual {:.3e} of {:.3e}, "
                                   "constraint residual {:.3e}); {}",
                                   settings.max_iterations, momentum_norm, force_scale, constraint_norm,
                                   newton_failure_advice(std::max(momentum_norm / force_scale, constraint_norm), 1, last_correction, settings));
      return result;
    }
    // Jacobian.
    triplets.clear();
    if (model.dof_count() > 0) {
      for (int col = 0; col < K.outerSize(); ++col)
        for (SparseMatrix::InnerIterator it(K, col); it; ++it) triplets.emplace_back(it.row(), col, it.value());
      const SparseMatrix& Mf = mass;
      for (int col = 0; col < Mf.outerSize(); ++col)
        for (SparseMatrix::InnerIterator it(Mf, col); it; ++it) triplets.emplace_back(it.row(), col, c * it.value());
    }
    // Every entry of a body's 18 x 18 block is inserted, zero or not: the sparsity must not change
    // between iterations, since UMFPACK's symbolic analysis is reused.
    for (Index b = 0; b < layout.bodies; ++b)
      for (int i = 0; i < 18; ++i)
        for (int j = 0; j < 18; ++j) triplets.emplace_back(layout.body(b) + i, layout.body(b) + j, body_rows[b].jacobian(i, j));
    Index r = 0;
    for (const FemJoint& joint : problem.joints)
      for (const FemJointRows& group : joint.rows) {
        const int count = group.kind == FemJointRows::Kind::coincide ? 3 : 1;
        for (int k = 0; k < count; ++k, ++r) {
          for (const auto& [unknown, value] : rows_mid.gradient[r]) triplets.emplace_back(unknown, layout.joints() + r, value);
          for (const auto& [unknown, value] : rows1.gradient[r]) triplets.emplace_back(layout.joints() + r, unknown, value);
        }
        // Axis rows are quadratic: the transpose term J(z_mid)^T lambda has the derivative
        // lambda/2 * alpha_i beta_j I between the directors of the two ends.
        if (group.kind == FemJointRows::Kind::perpendicular && group.a.kind == FemJointEndKind::body &&
            group.b.kind == FemJointEndKind::body) {
          const Real l = 0.5 * joint_lambda()[r - 1];
          for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
              for (int k = 0; k < 3; ++k) {
                const Real v = l * group.direction_a[i] * group.direction_b[j];
                triplets.emplace_back(layout.body(group.a.index) + 3 + 3 * i + k, layout.body(group.b.index) + 3 + 3 * j + k, v);
                triplets.emplace_back(layout.body(group.b.index) + 3 + 3 * j + k, layout.body(group.a.index) + 3 + 3 * i + k, v);
              }
        }
      }
    SparseMatrix A(n, n);
    A.setFromTriplets(triplets.begin(), triplets.end());
    A.makeCompressed();
    const bool factored = timed(result.solve_s, [&] { return solver.factorize(A); });
    if (!factored) {
      result.failure = "the coupled step's Jacobian is singular (a joint repeated, or a body held twice?)";
      return result;
    }
    const VectorX rhs = -R;
    const VectorX dz = timed(result.solve_s, [&] { return solver.solve(rhs); });
    ++result.iterations;
    Real alpha = 1;
    Configuration trial;
    for (int halving = 0;; ++halving, alpha *= 0.5) {
      trial = z;
      if (model.dof_count() > 0) add_free_part(model, alpha * dz.head(layout.free), trial.u);
      for (Index b = 0; b < layout.bodies; ++b) trial.q[b] += alpha * dz.segment<12>(layout.body(b));
      cells = assemble_solids(trial, true);
      if (cells.valid) break;
      if (halving == settings.max_halvings) {
        result.failure = fmt::format("every Newton correction inverts cell {} of '{}'", cells.invalid_cell, cells.invalid_solid);
        return result;
      }
    }
    // Size of the correction against the step's motion, for the round-off floor (as in step_dynamic).
    Real correction = 0, motion = 0;
    if (model.dof_count() > 0) {
      correction += (alpha * dz.head(layout.free)).squaredNorm();
      motion += free_part(model, trial.u - s0.u).squaredNorm();
    }
    for (Index b = 0; b < layout.bodies; ++b) {
      correction += (alpha * dz.segment<12>(layout.body(b))).squaredNorm();
      motion += (trial.q[b] - q0[b]).squaredNorm();
    }
    last_correction = std::sqrt(correction / std::max(motion, Real(1e-300)));
    z = trial;
    for (Index b = 0; b < layout.bodies; ++b) internal(b) += alpha * dz.segment<6>(layout.body(b) + 12);
    if (layout.joint_rows > 0) joint_lambda() += alpha * dz.tail(layout.joint_rows);
    const auto& norms = result.residual_norms;
    const bool stagnating = norms.size() >= 2 && norms.back() > 0.5 * norms[norms.size() - 2];
    if (stagnating && std::sqrt(correction) <= settings.tolerance * std::sqrt(motion)) break;
  }
  // Accept: velocities by the midpoint relation (prescribed dofs: the derivative of their values).
  if (model.dof_count() > 0) {
    FemDynamicState& s = run.solids;
    const VectorX u0 = s.u;
    s.v = (2 / h) * (z.u - u0) - s.v;
    apply_prescribed_velocity(model, s.time + h, s.v);
    s.u = z.u;
    s.energy = cells.energy;
  }
  run.solids.time += h;
  for (Index b = 0; b < layout.bodies; ++b) set_director_step(q0[b], v0[b], z.q[b], h, run.bodies[b]);
  result.converged = true;
  return result;
}

}  // namespace moreau
