#pragma once
// Quasi-static equilibrium f_int(u) = f_ext(t) by Newton's method with a backtracking line search
// (load stepping is the caller's sequence of t). Each iteration:
//   r = f_int(u) - f_ext(t) on the free dofs;   K du = -r;   u += alpha du
// alpha = 1, 1/2, 1/4, ... until the step leaves every cell valid and either the residual norm
// drops or the potential Pi(u) = W(u) - f_ext . u decreases by the Armijo condition
// Pi(u + alpha du) <= Pi(u) + 1e-4 alpha (r . du) (the residual test alone keeps Newton's full
// steps near the solution, where Pi's changes are below its round-off).
// When the prescribed displacements change, a predictor first carries their increment du_D into
// the interior by the linearised response K_ff du_f = -(r_f + K_fD du_D) (moving the boundary
// nodes alone would invert the cells next to them).
// Converged when |r| <= tolerance * max(|f_ext|, |f_int|, 1e-300) over all dofs (the reactions at
// prescribed dofs set the scale of a displacement-driven problem), or when the last correction
// was below tolerance * |u_free| (the residual's round-off floor is ~ eps |K| |u|; the correction
// criterion also ends a line search that finds no step at that floor).
#include <chrono>
#include <string>
#include <vector>

#include "moreau/fem/solids/fem_model.hpp"
#include "moreau/fem/core/linear_solver.hpp"

namespace moreau {

struct NewtonSettings {
  Real tolerance = 1e-10;
  int max_iterations = 25;
  int max_halvings = 12;
  int threads = 0;  // worker threads of the assembly (0 = all cores); results do not depend on it
};

struct NewtonResult {
  bool converged = false;
  int iterations = 0;                  // linear solves
  std::vector<Real> residual_norms;    // |r| before each solve and at the end
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

/// Equilibrium at load time t, starting from u (its prescribed dofs are overwritten with their
/// values at t). `solver` keeps its symbolic analysis between calls.
NewtonResult solve_static(const FemModel& model, Real t, VectorX& u, SparseSymmetricSolver& solver,
                          const NewtonSettings& settings = {});

}  // namespace moreau
