#include "moreau/fem/core/newton.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace moreau {

namespace {

// A trial's residual that is not finite, in words, with the system's reason if it gave one.
std::string not_finite_residual(const NewtonEvaluation& trial) {
  return trial.not_finite.empty() ? "a residual that is not finite" : "a residual that is not finite (" + trial.not_finite + ")";
}

// Below this size against the solution a full correction is taken without the line-search test.
constexpr Real kAsymptoticCorrection = 1e-6;

std::string smaller_steps_advice(const NewtonSettings& settings) {
  return fmt::format("take smaller steps (a smaller settings.dt; a static run applies its loads in steps of dt) or raise "
                     "settings.newton.max_iterations (now {})",
                     settings.max_iterations);
}

// Armijo's sufficient decrease of |R| or, for systems with one, of the potential.
bool sufficient_decrease(const NewtonEvaluation& now, const NewtonEvaluation& trial, Real alpha, Real potential_slope) {
  constexpr Real c = 1e-4;
  if (trial.converged || trial.norm <= (1 - c * alpha) * now.norm) return true;
  return std::isfinite(now.potential) && std::isfinite(trial.potential) &&
         trial.potential <= now.potential + c * alpha * potential_slope;
}

}  // namespace

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
  return smaller_steps_advice(settings);
}

bool newton_solve(NewtonSystem& system, const NewtonSettings& settings, const std::string& what, NewtonResult& result) {
  NewtonEvaluation now = system.evaluate(nullptr, 0);
  if (!now.valid) {
    result.failure = fmt::format("{} is inverted at the start of {}", now.invalid, what);
    return false;
  }
  const Real first = now.norm;
  Real last_correction = std::numeric_limits<Real>::infinity(), previous_norm = 0;
  VectorX dz;
  // The watchdog: a full step that raises |R| is taken once on trust; if the next full step does
  // not bring |R| below the level before it, the driver returns there and backtracks.
  bool watching = false;
  NewtonEvaluation checkpoint;
  VectorX checkpoint_dz;
  Real checkpoint_slope = 0;
  for (int iteration = 0;; ++iteration) {
    result.residual_norms.push_back(now.norm);
    if (now.converged) return true;
    if (!settings.line_search && (!std::isfinite(now.norm) || now.norm > 1e6 * first)) {
      result.failure = fmt::format("{} diverged ({}; the first residual was {:.3e})", what, now.describe, first);
      return false;
    }
    if (iteration == settings.max_iterations) {
      result.failure = fmt::format("{} did not converge in {} iterations ({}); {}", what, settings.max_iterations,
                                   now.describe, newton_failure_advice(now.relative, 1, last_correction, settings));
      return false;
    }
    if (!system.solve(dz, result.failure)) return false;
    ++result.iterations;
    Real slope = std::isfinite(now.potential) ? system.potential_slope(dz) : 0;
    bool accepted = false, any_valid = false;
    std::string inverted;
    NewtonEvaluation trial = system.evaluate(&dz, 1);
    Real alpha = 1;
    const bool full_step_valid = trial.valid && std::isfinite(trial.norm);
    if (full_step_valid) {
      any_valid = true;
      const NewtonEvaluation& reference = watching ? checkpoint : now;
      // A correction this small is Newton's quadratic regime, where |R| may sit on its round-off
      // floor (eps |J| |z|, far above the tolerance for a stiff body) and cannot show progress;
      // the corrections still shrink, and the stagnation rule ends the iteration.
      const bool asymptotic = system.relative_correction(dz, 1) <= kAsymptoticCorrection;
      if (!settings.line_search || asymptotic ||
          sufficient_decrease(reference, trial, 1, watching ? checkpoint_slope : slope)) {
        accepted = true;
        watching = false;
      } else if (!watching) {
        system.save();
        checkpoint = now;
        checkpoint_dz = dz;
        checkpoint_slope = slope;
        watching = accepted = true;
      } else {
        system.restore();
        now = checkpoint;
        dz = checkpoint_dz;
        slope = checkpoint_slope;
        watching = false;
      }
    } else {
      inverted = trial.valid ? not_finite_residual(trial) : trial.invalid;
    }
    for (int halving = 1; !accepted && halving <= settings.max_halvings; ++halving) {
      alpha *= 0.5;
      trial = system.evaluate(&dz, alpha);
      if (!trial.valid || !std::isfinite(trial.norm)) {
        inverted = trial.valid ? not_finite_residual(trial) : trial.invalid;
        continue;
      }
      any_valid = true;
      accepted = !settings.line_search || sufficient_decrease(now, trial, alpha, slope);
    }
    if (!accepted) {
      // On the residual's round-off floor no step reduces it, and the full correction is as small
      // as the noise: that is convergence by the correction criterion.
      const Real correction = system.relative_correction(dz, 1);
      if (any_valid && correction <= settings.tolerance) return true;
      if (!any_valid)
        result.failure = fmt::format("every Newton correction, down to 1/{} of it, gives {} ({}); {}", 1 << settings.max_halvings,
                                     inverted.starts_with("a residual that is not finite") ? inverted : "an inverted " + inverted,
                                     now.describe, smaller_steps_advice(settings));
      else
        result.failure = fmt::format("the line search found no step that reduces the residual of {} ({}, last correction "
                                     "{:.1e} of the solution); {}",
                                     what, now.describe, correction, newton_failure_advice(now.relative, 1, correction, settings));
      return false;
    }
    system.accept();
    last_correction = system.relative_correction(dz, alpha);
    // Stagnating: the residual this correction started from had not halved the one before.
    const bool stagnating = iteration > 0 && now.norm > 0.5 * previous_norm;
    previous_norm = now.norm;
    now = trial;
    if (stagnating && last_correction <= settings.tolerance && !watching) {
      result.residual_norms.push_back(now.norm);
      return true;
    }
  }
}

}  // namespace moreau
