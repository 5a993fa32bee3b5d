#pragma once
// One Newton driver for every nonlinear solve of the FEM engine (static equilibrium, dynamic
// steps, the coupled step of solids, bodies and joints, director bodies, the Navier-Stokes flow).
// A solve is a NewtonSystem: it evaluates its residual (and the Jacobian for the next solve) at
// trial iterates z + alpha dz and solves J dz = -R at the current one. The driver iterates
//   dz = -J^-1 R(z);   z <- z + alpha dz
// with a backtracking line search on the residual norm: alpha = 1, 1/2, 1/4, ... (at most
// max_halvings times) until the trial is valid (no inverted cell, a finite residual) and
//   |R(z + alpha dz)| <= (1 - 1e-4 alpha) |R(z)|    (Armijo's condition for 1/2 |R|^2, whose
//                                                   slope along the Newton direction is -|R|^2)
// or the system's potential, if it has one, decreases by Armijo's condition
//   Pi(z + alpha dz) <= Pi(z) + 1e-4 alpha dPi/dz . dz
// (near a solution Pi's changes sink below its round-off before |R|'s do; Nocedal & Wright,
// "Numerical Optimization", 2nd ed., sections 3.1 and 11.2).
// A watchdog keeps Newton's full steps where they work (Chamberlain, Powell, Lemarechal &
// Pedersen 1982; Nocedal & Wright section 15.6): a stiff body's first correction often raises |R|
// a hundredfold (its linearised rotation stretches it) and the next one brings it down by
// 1e-6. So a full step that fails the test is taken once on trust; unless the next full step
// satisfies the test against the level before the first, the driver returns to that iterate and
// backtracks along its correction. A full correction below 1e-6 of the solution is taken without
// the test: that is Newton's quadratic regime, where |R| may already sit on its round-off floor.
// The stagnation rule: a residual on its round-off floor stops falling. Once it has (|R| above
// half the previous one), a last correction below tolerance times the size of the solution (or of
// the step's motion) is convergence; so is a line search that finds no decrease with the full
// correction already below that size.
#include <chrono>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "moreau/math/types.hpp"

namespace moreau {

struct NewtonSettings {
  Real tolerance = 1e-10;
  int max_iterations = 25;
  int max_halvings = 12;
  bool line_search = true;  // false: every valid correction is taken whole (Picard iterations)
  int threads = 0;          // worker threads of the assembly (0 = all cores); results do not depend on it
};

struct NewtonResult {
  bool converged = false;
  int iterations = 0;                  // linear solves
  std::vector<Real> residual_norms;    // the residual measure before each solve and at the end
  Real energy = 0;                     // stored energy at the end, J
  std::string failure;                 // why it did not converge
  double assembly_s = 0, solve_s = 0;  // wall time in assembly (forces, tangents) and in factorize + solve
};

/// Adds the wall time of f() to `seconds` and returns f's result.
template <class F>
auto timed(double& seconds, F&& f) {
  const auto start = std::chrono::steady_clock::now();
  struct Add {
    double& s;
    std::chrono::steady_clock::time_point t0;
    ~Add() { s += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(); }
  } add{seconds, start};
  return f();
}

/// What a user can change when Newton stops at `residual` against its convergence scale, its last
/// correction having been `correction` times the size of the solution: the tolerance when the
/// residual is round-off (within 1e3 tolerances of its scale, or a correction below 1e-8), else
/// the step.
std::string newton_failure_advice(Real residual, Real scale, Real correction, const NewtonSettings& settings);

/// A system's residual at one iterate.
struct NewtonEvaluation {
  bool valid = true;      // false: the iterate is not admissible (an inverted cell)
  std::string invalid;    // where, when not valid ("cell 13 of 'bar'")
  Real norm = 0;          // |R|, the line search's measure
  bool converged = false; // the residual meets the system's tolerance
  Real relative = 0;      // the residual against its convergence scale (for the advice)
  std::string describe;   // the residual in words, for messages ("|R| = 1.2e-03, scale 4.5e+02")
  std::string not_finite; // why the residual is not finite, when the system knows ("node 3 of 'disc' left the mesh")
  Real potential = std::numeric_limits<Real>::quiet_NaN();  // Pi(z) if the system has one
};

class NewtonSystem {
 public:
  virtual ~NewtonSystem() = default;
  /// Evaluates the residual and, for the next solve, the Jacobian at z + alpha dz (`dz` null:
  /// at z itself, which the system then keeps as current). The driver makes the last evaluated
  /// trial current by accept().
  virtual NewtonEvaluation evaluate(const VectorX* dz, Real alpha) = 0;
  /// z <- the last evaluated trial.
  virtual void accept() = 0;
  /// Keeps the current iterate (and what was evaluated there), and returns to it.
  virtual void save() = 0;
  virtual void restore() = 0;
  /// Solves J dz = -R at the current iterate; false, with the reason in `failure`, if J is singular.
  virtual bool solve(VectorX& dz, std::string& failure) = 0;
  /// |alpha dz| against the size of the solution or of the step's motion (the stagnation rule).
  virtual Real relative_correction(const VectorX& dz, Real alpha) const = 0;
  /// dPi/dz . dz at the current iterate, for systems with a potential.
  virtual Real potential_slope(const VectorX& /*dz*/) const { return 0; }
};

/// A NewtonSystem whose iterate, with what was evaluated there (residual, tangent, ...), is one
/// value of type Iterate: now_ (current), trial_ (the trial evaluated last; evaluate() writes it
/// whole) and saved_. accept() swaps the trial in; save() and restore() copy.
template <class Iterate>
class NewtonIterates : public NewtonSystem {
 public:
  void accept() override { std::swap(now_, trial_); }
  void save() override { saved_ = now_; }
  void restore() override { now_ = saved_; }

 protected:
  Iterate now_{}, trial_{}, saved_{};
};

/// Newton's method on `system` from its current iterate (see above). Adds to result.iterations and
/// result.residual_norms; on failure result.failure says why and what to change. `what` names the
/// solve in messages ("the step", "the coupled step", ...).
bool newton_solve(NewtonSystem& system, const NewtonSettings& settings, const std::string& what, NewtonResult& result);

}  // namespace moreau
