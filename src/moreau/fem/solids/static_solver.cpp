#include "moreau/fem/solids/static_solver.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "moreau/fem/solids/fem_assembly.hpp"

namespace moreau {

std::string newton_failure_advice(Real residual, Real scale, Real correction, const NewtonSettings& settings) {
  const Real relative = residual / scale;
  if (relative <= 1e3 * settings.tolerance || correction <= 1e-8) {
    // A tolerance above the last correction converges by the correction criterion; else one
    // above the residual's relative size by the residual test.
    const Real needed = correction <= 1e-8 ? correction : relative;
    const Real suggested = std::min(Real(1e-2), std::pow(10.0, std::ceil(std::log10(2 * needed))));
    return fmt::format("the residual is {:.1e} of its scale, close to its round-off floor: raise settings.newton.tolerance "
                       "(now {:.0e}) to about {:.0e}",
                       relative, settings.tolerance, suggested);
  }
  return fmt::format("take smaller steps (a smaller settings.dt; a static run applies its loads in steps of dt) or raise "
                     "settings.newton.max_iterations (now {})",
                     settings.max_iterations);
}

NewtonResult solve_static(const FemModel& model, Real t, VectorX& u, SparseSymmetricSolver& solver,
                          const NewtonSettings& settings) {
  NewtonResult result;
  Real last_correction = std::numeric_limits<Real>::infinity();  // |alpha du| / |u_free| of the last step
  const VectorX f_ext = external_forces(model, t);
  VectorX f_int, trial_force;
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
  for (;;) {
    const VectorX r = free_part(model, f_int - f_ext);
    const Real norm = r.norm();
    result.residual_norms.push_back(norm);
    result.energy = state.energy;
    const Real scale = std::max({f_ext.norm(), f_int.norm(), Real(1e-300)});
    if (norm <= settings.tolerance * scale) {
      result.converged = true;
      return result;
    }
    if (result.iterations == settings.max_iterations) {
      result.failure = fmt::format("no convergence in {} Newton iterations (|r| = {:.3e}, scale {:.3e}); {}",
                                   settings.max_iterations, norm, scale, newton_failure_advice(norm, scale, last_correction, settings));
      return result;
    }
    if (!timed(result.solve_s, [&] { return solver.factorize(K); })) {
      result.failure = "the tangent is singular (is the body held against rigid motion?)";
      return result;
    }
    const VectorX du = timed(result.solve_s, [&] { return solver.solve(-r); });
    ++result.iterations;
    const Real potential = state.energy - f_ext.dot(u);
    const Real slope = r.dot(du);
    Real alpha = 2;
    VectorX trial;
    bool accepted = false, any_valid = false;
    for (int halving = 0; halving <= settings.max_halvings && !accepted; ++halving) {
      alpha *= 0.5;
      trial = u;
      add_free_part(model, alpha * du, trial);
      const InternalForceResult trial_state = timed(result.assembly_s, [&] { return assemble_internal_forces(model, trial, trial_force, nullptr, settings.threads); });
      if (!trial_state.valid) continue;
      any_valid = true;
      const Real trial_norm = free_part(model, trial_force - f_ext).norm();
      const Real trial_potential = trial_state.energy - f_ext.dot(trial);
      accepted = trial_norm < norm || trial_potential <= potential + 1e-4 * alpha * slope;
    }
    if (!accepted) {
      // Near the solution the residual is round-off (~ eps lambda h per dof for a nearly
      // incompressible body): no step reduces it, and Newton's correction is as small as the
      // noise. A correction below tolerance * |u| is convergence by the correction criterion.
      const Real correction = du.norm() / std::max(free_part(model, u).norm(), Real(1e-300));
      if (any_valid && correction <= settings.tolerance) {
        result.converged = true;
        return result;
      }
      result.failure = fmt::format("the line search found no step that reduces the residual (|r| = {:.3e}, scale {:.3e}, "
                                   "last correction {:.1e} of |u|); {}",
                                   norm, scale, correction, newton_failure_advice(norm, scale, correction, settings));
      return result;
    }
    u = trial;
    last_correction = alpha * du.norm() / std::max(free_part(model, u).norm(), Real(1e-300));
    state = timed(result.assembly_s, [&] { return assemble_internal_forces(model, u, f_int, &K, settings.threads); });
    // A correction below tolerance * |u| is converged even where the residual sits on its
    // round-off floor (~ eps |K| |u|, above tolerance * |f| for stiff or lightly loaded bodies).
    const bool stagnating = result.residual_norms.size() >= 2 &&
                            norm > 0.5 * result.residual_norms[result.residual_norms.size() - 2];
    if (stagnating && last_correction <= settings.tolerance) {
      result.residual_norms.push_back(free_part(model, f_int - f_ext).norm());
      result.energy = state.energy;
      result.converged = true;
      return result;
    }
  }
}

}  // namespace moreau
