#pragma once
// One time step of solids, director rigid bodies and the joints between them, solved as one
// Newton system. Unknowns: the solids' free dofs u1, each body's q1 (12) and
// internal multipliers (6), and the joints' multipliers. Residuals, all in force units:
//   solids  M (2/h^2 (u1 - u0) - 2/h v0) + f_algo(u0, u1) - f_ext + J_u^T lambda_j
//   bodies  M_b (2/h^2 (q1 - q0) - 2/h v0) + G(q_m)^T lambda_int - f_b + J_q(q_m)^T lambda_j
//   internal constraints g(q1) = 0, joints g_j(u1, q1) = 0
// The Jacobian is not symmetric (UMFPACK). Rigid bodies without joints are stepped the same way.
#include <vector>

#include "moreau/fem/bodies/fem_joints.hpp"
#include "moreau/fem/scene/fem_problem.hpp"
#include "moreau/fem/core/linear_solver.hpp"

namespace moreau {

/// Advances solids and bodies together by h; on failure the state is unchanged. `solver` keeps
/// the coupled system's symbolic analysis between steps (its sparsity does not change).
NewtonResult step_coupled(const FemProblem& problem, const SparseMatrix& mass, StepRule rule, Real h,
                          FemRunState& run, SparseLuSolver& solver, const NewtonSettings& settings);

/// Largest violation of a joint's rows at the current state (m, or the cosine for axis rows).
Real joint_violation(const FemProblem& problem, const FemRunState& run, const FemJoint& joint);

}  // namespace moreau
