// XPBD projection of distance: the scalar update with sum_i w_i |grad_i C|^2 = w0 + w1 (|n| = 1).
// A closed form of the generic row projection (project_rows.hpp) for this family's rows; the
// test XpbdKernels.AgreeWithTheGenericRowProjection holds the two together.
#include "moreau/solvers/xpbd/particle_projections.hpp"

namespace moreau {

void xpbd_project(const DistanceConstraints& c, Real* lambda, const SubstepContext& s) {
  for_each_by_color(c.batches, [&](Index k) {
    const auto [a, b] = c.particles[k];
    const Real wa = s.inv_mass[a], wb = s.inv_mass[b];
    const auto [C, n] = evaluate_distance(s.x[a], s.x[b], c.rest_length[k]);
    const Real tau = c.damping_time[k];
    const Real grad_dot_dx = tau > 0 ? n.dot((s.x[a] - s.x_start[a]) - (s.x[b] - s.x_start[b])) : 0;
    const Real dl = xpbd_delta_lambda(C, lambda[k], c.compliance[k], tau, s, wa + wb, grad_dot_dx);
    lambda[k] += dl;
    s.x[a] += (wa * dl) * n;
    s.x[b] -= (wb * dl) * n;
  });
}

}  // namespace moreau
