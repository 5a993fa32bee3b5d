#pragma once
// Quasi-static equilibrium f_int(u) = f_ext(t) by the Newton driver (fem/core/newton.hpp; load
// stepping is the caller's sequence of t). Each iteration:
//   r = f_int(u) - f_ext(t) on the free dofs;   K du = -r;   u += alpha du
// with the line search on |r| or on the potential Pi(u) = W(u) - f_ext . u (slope r . du).
// When the prescribed displacements change, a predictor first carries their increment du_D into
// the interior by the linearised response K_ff du_f = -(r_f + K_fD du_D) (moving the boundary
// nodes alone would invert the cells next to them).
// Converged when |r| <= tolerance * max(|f_ext|, |f_int|, 1e-300) over all dofs (the reactions at
// prescribed dofs set the scale of a displacement-driven problem), or when the last correction
// was below tolerance * |u_free| (the residual's round-off floor is ~ eps |K| |u|; the correction
// criterion also ends a line search that finds no step at that floor).
#include <string>
#include <vector>

#include "moreau/fem/core/newton.hpp"
#include "moreau/fem/solids/fem_model.hpp"
#include "moreau/fem/core/linear_solver.hpp"

namespace moreau {

/// Equilibrium at load time t, starting from u (its prescribed dofs are overwritten with their
/// values at t). `solver` keeps its symbolic analysis between calls.
NewtonResult solve_static(const FemModel& model, Real t, VectorX& u, SparseSymmetricSolver& solver,
                          const NewtonSettings& settings = {});

}  // namespace moreau
