#include "moreau/fem/solids/static_solver.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "moreau/fem/core/newton.hpp"
#include "moreau/fem/solids/fem_assembly.hpp"

namespace moreau {

namespace {

// Equilibrium r(u) = f_int(u) - f_ext on the free dofs, with the potential Pi = W(u) - f_ext . u.
class StaticSystem final : public NewtonSystem {
 public:
  StaticSystem(const FemModel& model, const VectorX& f_ext, VectorX& u, SparseSymmetricSolver& solver,
               const NewtonSettings& settings, NewtonResult& result)
      : model_(model), f_ext_(f_ext), u_(u), solver_(solver), settings_(settings), result_(result) {}

  // The state at u, already assembled by the caller.
  void take(InternalForceResult state, VectorX f_int, SparseMatrix K) {
    state_ = std::move(state);
    f_int_ = std::move(f_int);
    K_ = std::move(K);
  }

  NewtonEvaluation evaluate(const VectorX* du, Real alpha) override {
    if (!du) return measure(u_, f_int_, state_);
    trial_u_ = u_;
    add_free_part(model_, alpha * *du, trial_u_);
    trial_state_ = timed(result_.assembly_s, [&] {
      return assemble_internal_forces(model_, trial_u_, trial_f_, &trial_K_, settings_.threads);
    });
    return measure(trial_u_, trial_f_, trial_state_);
  }

  void accept() override {
    u_ = trial_u_;
    state_ = trial_state_;
    std::swap(f_int_, trial_f_);
    std::swap(K_, trial_K_);
  }

  void save() override { saved_ = {u_, state_, f_int_, K_}; }
  void restore() override {
    u_ = saved_.u;
    state_ = saved_.state;
    f_int_ = saved_.f_int;
    K_ = saved_.K;
  }

  bool solve(VectorX& du, std::string& failure) override {
    if (!timed(result_.solve_s, [&] { return solver_.factorize(K_); })) {
      failure = "the tangent is singular (is the body held against rigid motion?)";
      return false;
    }
    du = timed(result_.solve_s, [&] { return solver_.solve(-residual()); });
    return true;
  }

  Real relative_correction(const VectorX& du, Real alpha) const override {
    return alpha * du.norm() / std::max(free_part(model_, u_).norm(), Real(1e-300));
  }
  // dPi/du . du = r . du
  Real potential_slope(const VectorX& du) const override { return residual().dot(du); }

  Real energy() const { return state_.energy; }

 private:
  NewtonEvaluation measure(const VectorX& u, const VectorX& f_int, const InternalForceResult& state) const {
    NewtonEvaluation e;
    e.valid = state.valid;
    if (!e.valid) {
      e.invalid = fmt::format("cell {} of '{}'", state.invalid_cell, state.invalid_solid);
      return e;
    }
    const Real scale = std::max({f_ext_.norm(), f_int.norm(), Real(1e-300)});
    e.norm = free_part(model_, f_int - f_ext_).norm();
    e.converged = e.norm <= settings_.tolerance * scale;
    e.relative = e.norm / scale;
    e.describe = fmt::format("|r| = {:.3e}, scale {:.3e}", e.norm, scale);
    e.potential = state.energy - f_ext_.dot(u);
    return e;
  }

  VectorX residual() const { return free_part(model_, f_int_ - f_ext_); }

  const FemModel& model_;
  const VectorX& f_ext_;
  VectorX& u_;
  SparseSymmetricSolver& solver_;
  const NewtonSettings& settings_;
  NewtonResult& result_;
  InternalForceResult state_, trial_state_;
  VectorX f_int_, trial_f_, trial_u_;
  SparseMatrix K_, trial_K_;
  struct {
    VectorX u;
    InternalForceResult state;
    VectorX f_int;
    SparseMatrix K;
  } saved_;
};

}  // namespace

NewtonResult solve_static(const FemModel& model, Real t, VectorX& u, SparseSymmetricSolver& solver,
                          const NewtonSettings& settings) {
  NewtonResult result;
  const VectorX f_ext = external_forces(model, t);
  VectorX f_int;
  SparseMatrix K;
  InternalForceResult state = timed(result.assembly_s, [&] { return assemble_internal_forces(model, u, f_int, &K, settings.threads); });
  if (!state.valid) {
    result.failure = fmt::format("cell {} of '{}' is inverted at the start of the solve", state.invalid_cell,
                                 state.invalid_solid);
    return result;
  }
  // Predictor for changed prescribed values: moving only the boundary nodes would squash the cells
  // next to them; the linearised response carries the increment into the interior,
  //   K_ff du_f = -(r_f + K_fD du_D).
  VectorX target = u;
  apply_prescribed(model, t, target);
  const VectorX du_D = target - u;
  if (du_D.squaredNorm() > 0 && model.free_count == 0) {
    u = target;
    state = timed(result.assembly_s, [&] { return assemble_internal_forces(model, u, f_int, &K, settings.threads); });
  } else if (du_D.squaredNorm() > 0) {
    if (!timed(result.solve_s, [&] { return solver.factorize(K); })) {
      result.failure = "the tangent is singular (is the body held against rigid motion?)";
      return result;
    }
    const VectorX rhs = free_part(model, f_int - f_ext + tangent_times(model, u, du_D));
    u = target;
    add_free_part(model, timed(result.solve_s, [&] { return solver.solve(-rhs); }), u);
    ++result.iterations;
    state = timed(result.assembly_s, [&] { return assemble_internal_forces(model, u, f_int, &K, settings.threads); });
    if (!state.valid) {
      result.failure = fmt::format("the prescribed displacements invert cell {} of '{}'; take smaller load steps",
                                   state.invalid_cell, state.invalid_solid);
      return result;
    }
  }
  StaticSystem system(model, f_ext, u, solver, settings, result);
  system.take(std::move(state), std::move(f_int), std::move(K));
  result.converged = newton_solve(system, settings, "the solve", result);
  result.energy = system.energy();
  return result;
}

}  // namespace moreau
