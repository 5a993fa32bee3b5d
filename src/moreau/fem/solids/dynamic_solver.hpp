#pragma once
// One time step of nonlinear elastodynamics, for the implicit midpoint rule
// and the energy-momentum scheme, which differ only in the algorithmic internal force
// (solid_element_step):
//   u_n+1 - u_n = h/2 (v_n + v_n+1)
//   M (v_n+1 - v_n) = h (f_ext(t_n+1/2) - f_algo(u_n, u_n+1))
// Eliminating v_n+1 leaves, for the free dofs of u_n+1,
//   R = M (2/h^2 (u_n+1 - u_n) - 2/h v_n) + f_algo - f_ext = 0,   dR/du_n+1 = 2/h^2 M + K_algo,
// solved by Newton from the predictor u_n + h v_n (or u_n, if that inverts a cell); prescribed dofs
// take their values at t_n+1 and every v_n+1 follows from the first equation. Converged when
// |R| <= tolerance * max(|M a|, |f_algo|, |f_ext|) or the correction is below tolerance times the
// step's displacement |u_n+1 - u_n|.
#include "moreau/fem/solids/fem_model.hpp"
#include "moreau/fem/core/linear_solver.hpp"
#include "moreau/fem/solids/solid_element.hpp"
#include "moreau/fem/solids/static_solver.hpp"

namespace moreau {

struct FemDynamicState {
  VectorX u, v;     // displacement (m) and velocity (m/s) of every dof
  Real time = 0;    // s
  Real energy = 0;  // stored energy at `time`, J
};

/// A state at rest in the reference configuration (prescribed dofs at their values and velocities
/// at t = 0).
FemDynamicState initial_dynamic_state(const FemModel& model);

/// The starting guess of a step's u_n+1 (free solids: their fitted rigid motion, rotated by
/// exp(h w); held solids: u_n + h v_n). Prescribed dofs are the caller's.
VectorX dynamic_step_predictor(const FemModel& model, const VectorX& u0, const VectorX& v0, Real h);

/// Advances `state` by h. `mass` is assemble_mass_matrix(model). On failure the state is unchanged.
NewtonResult step_dynamic(const FemModel& model, const SparseMatrix& mass, StepRule rule, Real h,
                          FemDynamicState& state, SparseSymmetricSolver& solver, const NewtonSettings& settings = {});

/// Kinetic energy 1/2 v^T M v (consistent mass), J.
Real kinetic_energy(const FemModel& model, const VectorX& v);

/// Linear momentum sum_ab M_ab v_b and angular momentum about the origin sum_ab M_ab x_a x v_b
/// (x = X + u), both 3-vectors (in 2D the angular momentum is along z).
void momenta(const FemModel& model, const VectorX& u, const VectorX& v, Vec3& linear, Vec3& angular);

}  // namespace moreau
