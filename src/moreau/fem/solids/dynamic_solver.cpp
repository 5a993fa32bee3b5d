#include "moreau/fem/solids/dynamic_solver.hpp"

#include <fmt/format.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <limits>

#include "moreau/fem/core/newton.hpp"
#include "moreau/fem/solids/fem_assembly.hpp"

namespace moreau {

FemDynamicState initial_dynamic_state(const FemModel& model) {
  FemDynamicState s;
  s.u = VectorX::Zero(model.dof_count());
  s.v = VectorX::Zero(model.dof_count());
  apply_prescribed(model, 0, s.u);
  apply_prescribed_velocity(model, 0, s.v);
  return s;
}

// Predictor of a step. A solid without prescribed dofs moves its nodes by the rigid motion that
// fits its velocities (the centre's velocity and w = I^-1 L about the centre, with the node
// masses, the row sums of the consistent mass), rotating them by exp(h w). Moving along straight lines
// instead (u0 + h v0) stretches a spinning body by (w h)^2 / 2, and the midpoint rule's end
// velocities are not a rigid field even for a rigid motion, so adding h times their non-rigid
// part stretches it by O(h^2 w^2); a stiff body answers either with stresses so large that
// Newton's linearised rotations cannot recover. The elastic part of the motion is left to Newton.
// Held solids use u0 + h v0.
VectorX dynamic_step_predictor(const FemModel& model, const VectorX& u0, const VectorX& v0, Real h) {
  VectorX u1 = u0 + h * v0;
  if (model.dim != 3) return u1;
  const std::vector<Real>& lumped = model.node_mass;
  for (const FemSolid& s : model.solids) {
    const Index first = s.node_begin, count = s.mesh.node_count();
    bool held = false;
    for (Index n = first; n < first + count && !held; ++n)
      for (int k = 0; k < 3; ++k) held = held || model.free_index[model.dof(n, k)] < 0;
    if (held) continue;
    auto x = [&](Index n) { return Vec3(s.mesh.nodes[n - first] + u0.segment<3>(3 * n)); };
    Real m = 0;
    Vec3 c = Vec3::Zero(), p = Vec3::Zero();
    for (Index n = first; n < first + count; ++n) {
      m += lumped[n];
      c += lumped[n] * x(n);
      p += lumped[n] * v0.segment<3>(3 * n);
    }
    c /= m;
    const Vec3 vc = p / m;
    Vec3 L = Vec3::Zero();
    Mat3 I = Mat3::Zero();
    for (Index n = first; n < first + count; ++n) {
      const Vec3 r = x(n) - c;
      L += lumped[n] * r.cross(v0.segment<3>(3 * n) - vc);
      I += lumped[n] * (r.squaredNorm() * Mat3::Identity() - r * r.transpose());
    }
    const Vec3 w = I.ldlt().solve(L);
    const Real angle = h * w.norm();
    const Mat3 R = angle > 0 ? Mat3(Eigen::AngleAxisd(angle, w.normalized())) : Mat3::Identity();
    for (Index n = first; n < first + count; ++n) {
      const Vec3 r = x(n) - c;
      const Vec3 x1 = c + h * vc + R * r;
      u1.segment<3>(3 * n) = x1 - s.mesh.nodes[n - first];
    }
  }
  return u1;
}

namespace {

// The step's residual on the free dofs of u_n+1,
//   R = M (2/h^2 (u_n+1 - u_n) - 2/h v_n) + f_algo(u_n, u_n+1) - f_ext,   dR/du_n+1 = 2/h^2 M + K_algo.
struct DynamicStepIterate {
  VectorX u1, f, R;           // u_n+1, the algorithmic internal force there, the residual
  SparseMatrix K;             // the algorithmic tangent
  InternalForceResult cells;  // energy and validity of the cells
};

class DynamicStepSystem final : public NewtonIterates<DynamicStepIterate> {
 public:
  DynamicStepSystem(const FemModel& model, const SparseMatrix& mass, StepRule rule, Real h, const FemDynamicState& start,
                    const VectorX& f_ext, SparseSymmetricSolver& solver, const NewtonSettings& settings,
                    NewtonResult& result)
      : model_(model), mass_(mass), rule_(rule), h_(h), start_(start), f_ext_(f_ext), solver_(solver),
        settings_(settings), result_(result) {}

  // The iterate u_n+1 with its assembled forces and tangent.
  void take(VectorX u1, VectorX f, SparseMatrix K, const InternalForceResult& cells) {
    now_.u1 = std::move(u1);
    now_.f = std::move(f);
    now_.K = std::move(K);
    now_.cells = cells;
  }

  NewtonEvaluation evaluate(const VectorX* du, Real alpha) override {
    if (!du) return measure(now_);
    trial_.u1 = now_.u1;
    add_free_part(model_, alpha * *du, trial_.u1);
    trial_.cells = timed(result_.assembly_s, [&] {
      return assemble_step_forces(model_, start_.u, trial_.u1, rule_, trial_.f, &trial_.K, settings_.threads);
    });
    return measure(trial_);
  }

  bool solve(VectorX& du, std::string& failure) override {
    // dR/du = 2/h^2 M + K_algo: the two matrices share the structure of model.pattern.
    const Real c = 2 / (h_ * h_);
    SparseMatrix& K = now_.K;
    for (Index i = 0; i < K.nonZeros(); ++i) K.valuePtr()[i] += c * mass_.valuePtr()[i];
    if (!timed(result_.solve_s, [&] { return solver_.factorize(K, rule_ == StepRule::midpoint); })) {
      failure = solver_.failure().empty() ? "the step's tangent is singular" : solver_.failure();
      return false;
    }
    if (!timed(result_.solve_s, [&] { return solver_.solve(-now_.R, du); })) {
      failure = solver_.failure();
      return false;
    }
    return true;
  }

  Real relative_correction(const VectorX& du, Real alpha) const override {
    return alpha * du.norm() / std::max(free_part(model_, now_.u1 - start_.u).norm(), Real(1e-300));
  }

  const VectorX& displacement() const { return now_.u1; }
  const InternalForceResult& cells() const { return now_.cells; }

 private:
  // Validity and the residual R of an iterate whose forces are assembled (writes it.R).
  NewtonEvaluation measure(DynamicStepIterate& it) const {
    const VectorX& u1 = it.u1;
    const VectorX& f = it.f;
    const InternalForceResult& cells = it.cells;
    VectorX& R = it.R;
    NewtonEvaluation e;
    e.valid = cells.valid;
    if (!e.valid) {
      e.invalid = fmt::format("cell {} of '{}'", cells.invalid_cell, cells.invalid_solid);
      return e;
    }
    const VectorX inertia = mass_times(model_, (2 / (h_ * h_)) * (u1 - start_.u) - (2 / h_) * start_.v);
    R = free_part(model_, inertia + f - f_ext_);
    const Real scale = std::max({inertia.norm(), f.norm(), f_ext_.norm(), Real(1e-300)});
    e.norm = R.norm();
    e.converged = e.norm <= settings_.tolerance * scale;
    e.relative = e.norm / scale;
    e.describe = fmt::format("|R| = {:.3e}, scale {:.3e}", e.norm, scale);
    return e;
  }

  const FemModel& model_;
  const SparseMatrix& mass_;
  StepRule rule_;
  Real h_;
  const FemDynamicState& start_;
  const VectorX& f_ext_;
  SparseSymmetricSolver& solver_;
  const NewtonSettings& settings_;
  NewtonResult& result_;
};

}  // namespace

NewtonResult step_dynamic(const FemModel& model, const SparseMatrix& mass, StepRule rule, Real h,
                          FemDynamicState& state, SparseSymmetricSolver& solver, const NewtonSettings& settings) {
  NewtonResult result;
  const VectorX& u0 = state.u;
  const VectorX& v0 = state.v;
  const VectorX f_ext = external_forces(model, state.time + 0.5 * h);
  VectorX u1 = dynamic_step_predictor(model, u0, v0, h);
  apply_prescribed(model, state.time + h, u1);
  VectorX f;
  SparseMatrix K;
  InternalForceResult cells = timed(result.assembly_s, [&] { return assemble_step_forces(model, u0, u1, rule, f, &K, settings.threads); });
  if (!cells.valid) {
    u1 = u0;
    apply_prescribed(model, state.time + h, u1);
    cells = timed(result.assembly_s, [&] { return assemble_step_forces(model, u0, u1, rule, f, &K, settings.threads); });
    if (!cells.valid) {
      result.failure = fmt::format("cell {} of '{}' is inverted at the start of the step", cells.invalid_cell,
                                   cells.invalid_solid);
      return result;
    }
  }
  DynamicStepSystem system(model, mass, rule, h, state, f_ext, solver, settings, result);
  system.take(std::move(u1), std::move(f), std::move(K), cells);
  if (!newton_solve(system, settings, "the step", result)) return result;
  u1 = system.displacement();
  cells = system.cells();
  result.converged = true;
  result.energy = cells.energy;
  state.v = (2 / h) * (u1 - u0) - v0;
  // The recursion above would carry an error in a prescribed dof's velocity forever (a ramp
  // u = c t started from rest alternates 2c, 0, 2c, ...); prescribed dofs take the derivative of
  // their values instead.
  apply_prescribed_velocity(model, state.time + h, state.v);
  state.u = u1;
  state.time += h;
  state.energy = cells.energy;
  return result;
}

Real kinetic_energy(const FemModel& model, const VectorX& v) { return 0.5 * v.dot(mass_times(model, v)); }

void momenta(const FemModel& model, const VectorX& u, const VectorX& v, Vec3& linear, Vec3& angular) {
  // p = sum_a (M v)_a and L = sum_a x_a x (M v)_a: the consistent mass couples a node's position
  // with its neighbours' velocities, and (M v)_a collects exactly those products.
  const VectorX Mv = mass_times(model, v);
  linear.setZero();
  angular.setZero();
  for (Index n = 0; n < model.node_count; ++n) {
    Vec3 x = model.reference_position(n), p = Vec3::Zero();
    for (int k = 0; k < model.dim; ++k) {
      x[k] += u[model.dof(n, k)];
      p[k] = Mv[model.dof(n, k)];
    }
    linear += p;
    angular += x.cross(p);
  }
}

}  // namespace moreau
