#pragma once
// XPBD's projection of the shape-matching clusters (shape_matching/shape_matching.hpp): each
// cluster in turn, Gauss-Seidel. Each entry (particle i of a cluster) is the vector constraint
// C = x_i - g_i with compliance alpha = 1/(m_i omega^2), its goal g_i held while it is corrected:
//   dlambda = (-C - alpha~ lambda) / (w_i + alpha~),  alpha~ = alpha / h^2,  x_i += w_i dlambda,
// lambda accumulated over the substep's iterations (Macklin et al. 2016, eq. 18). The first
// iteration moves x_i the share s = omega^2 h^2 / (1 + omega^2 h^2) of the way to g_i; further
// iterations converge to the implicit step rather than compounding the pull. alpha~ lambda_i is
// the sum of x_i's corrections over omega^2 h^2, the same for every mass, so each correction
// still sums to zero momentum.
#include "moreau/solvers/xpbd/substep_context.hpp"

namespace moreau {

struct Model;
struct GrainSleepState;

/// One pass over every cluster; call from every thread of the parallel region. Clusters that
/// share no particle (clumps, separate objects) are spread over the threads; overlapping ones are
/// projected in order on one thread. `lambda` holds one multiplier per cluster entry, zeroed at
/// the start of the substep. A sleeping clump (its first sphere asleep: a clump sleeps whole) is
/// skipped: it keeps the place it fell asleep in.
void project_shape_matching(const Model& model, const GrainSleepState& sleep, const SubstepContext& s, Vec3* lambda);

}  // namespace moreau
