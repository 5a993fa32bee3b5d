#pragma once
// One XPBI iteration over the continuum's particles (Yu et al. 2024, Alg. 1, the loop of line 4):
// each particle's elastoplastic constraint, then its anti-clumping pairs, Gauss-Seidel by block
// colour (continuum_neighborhood.hpp). In the positions x = x^n + h v that the XPBD substep
// corrects (solvers/xpbd/substep_context.hpp), with d = x - x^n the motion over the substep:
//
//   h grad v_p = sum_b V_b^n (d_b - d_p) (L_p grad W_b)^T,   F_p = Z((I + h grad v_p) F_p^n),
//   C_p = sqrt(2 Psi(F_p)),   compliance 1 / V_p^0 (so that C^2 / (2 alpha) = V^0 Psi),
//   grad_{x_b} C_p = V_b^n (dC/dF) (F_p^n)^T L_p grad W_b,  grad_{x_p} C_p = -sum_b grad_{x_b} C_p,
//   dC/dF = P(F_p) / C_p,   Z held constant,
//   dlambda = (-C - alpha~ lambda) / (sum_b w_b |grad_b C|^2 + alpha~),  x_b += w_b grad_b C dlambda.
// The paper's velocity update dv_b = w_b grad_b C dlambda / h is the same correction: x = x^n + h v.
// Anti-clumping (the paper's eq. 21): two particles closer than min_distance r are pushed apart,
// mass-weighted, to that distance.
#include <vector>

#include "moreau/solvers/xpbd/substep_context.hpp"
#include "moreau/solvers/xpbi/continuum_neighborhood.hpp"

namespace moreau {

/// Every thread of a parallel region calls it; `lambda` holds each sweep position's multiplier of this
/// substep (zero at its start).
void sweep_continuum(const Model& model, const State& state, const ContinuumNeighborhood& around,
                     const SubstepContext& ctx, std::vector<Real>& lambda);

}  // namespace moreau
