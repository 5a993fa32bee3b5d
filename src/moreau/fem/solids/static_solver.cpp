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
struct StaticIterate {
  VectorX u, f_int;            // the displacement and the internal force there
  SparseMatrix K;              // the tangent
  InternalForceResult state;   // energy and validity of the cells
};

class StaticSystem final : public NewtonIterates<StaticIterate> {
 public:
  StaticSystem(const FemModel& model, const VectorX& f_ext, SparseSymmetricSolver& solver,
               const NewtonSettings& settings, NewtonResult& result)
      : model_(model), f_ext_(f_ext), solver_(solver), settings_(settings), result_(result) {}

  // The state at u, already assembled by the caller.
  void take(VectorX u, InternalForceResult state, VectorX f_int, SparseMatrix K) {
    now_.u = std::move(u);
    now_.state = std::move(state);
    now_.f_int = std::move(f_int);
    now_.K = std::move(K);
  }

  NewtonEvaluation evaluate(const VectorX* du, Real alpha) override {
    if (!du) return measure(now_);
    trial_.u = now_.u;
    add_free_part(model_, alpha * *du, trial_.u);
    trial_.state = timed(result_.assembly_s, [&] {
      return assemble_internal_forces(model_, trial_.u, trial_.f_int, &trial_.K, settings_.threads);
    });
    return measure(trial_);
  }

  bool solve(VectorX& du, std::string& failure) override {
    if (!timed(result_.solve_s, [&] { return solver_.factorize(now_.K); })) {
      failure = solver_.failure().empty() ? "the tangent is singular (is the body held against rigid motion?)"
                                          : solver_.failure();
      return false;
    }
    if (!timed(result_.solve_s, [&] { return solver_.solve(-residual(), du); })) {
      failure = solver_.failure();
      return false;
    }
    return true;
  }

  Real relative_correction(const VectorX& du, Real alpha) const override {
    return alpha * du.norm() / std::max(free_part(model_, now_.u).norm(), Real(1e-300));
  }
  // dPi/du . du = r . du
  Real potential_slope(const VectorX& du) const override { return residual().dot(du); }

  Real energy() const { return now_.state.energy; }
  const VectorX& displacement() const { return now_.u; }

 private:
  NewtonEvaluation measure(const StaticIterate& it) const {
    const VectorX& u = it.u;
    const VectorX& f_int = it.f_int;
    const InternalForceResult& state = it.state;
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

  VectorX residual() const { return free_part(model_, now_.f_int - f_ext_); }

  const FemModel& model_;
  const VectorX& f_ext_;
  SparseSymmetricSolver& solver_;
  const NewtonSettings& settings_;
  NewtonResult& result_;
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
      result.failure = solver.failure().empty() ? "the tangent is singular (is the body held against rigid motion?)"
                                                : solver.failure();
      return result;
    }
    const VectorX rhs = free_part(model, f_int - f_ext + tangent_times(model, u, du_D));
    VectorX du_f;
    if (!timed(result.solve_s, [&] { return solver.solve(-rhs, du_f); })) {
      result.failure = solver.failure();
      return result;
    }
    u = target;
    add_free_part(model, du_f, u);
    ++result.iterations;
    state = timed(result.assembly_s, [&] { return assemble_internal_forces(model, u, f_int, &K, settings.threads); });
    if (!state.valid) {
      result.failure = fmt::format("the prescribed displacements invert cell {} of '{}'; take smaller load steps",
                                   state.invalid_cell, state.invalid_solid);
      return result;
    }
  }
  StaticSystem system(model, f_ext, solver, settings, result);
  system.take(u, std::move(state), std::move(f_int), std::move(K));
  result.converged = newton_solve(system, settings, "the solve", result);
  u = system.displacement();
  result.energy = system.energy();
  return result;
}

}  // namespace moreau
