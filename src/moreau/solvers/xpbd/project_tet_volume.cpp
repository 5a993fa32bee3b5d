// XPBD projection of tet volume: the scalar update.
// A closed form of the generic row projection (project_rows.hpp) for this family's rows; the
// test XpbdKernels.AgreeWithTheGenericRowProjection holds the two together.
#include "moreau/solvers/xpbd/particle_projections.hpp"

namespace moreau {

void xpbd_project(const TetVolumeConstraints& c, Real* lambda, const SubstepContext& s) {
  for_each_by_color(c.batches, [&](Index k) {
    const auto& p = c.particles[k];
    const TetVolumeValue v = evaluate_tet_volume({s.x[p[0]], s.x[p[1]], s.x[p[2]], s.x[p[3]]}, c.rest_inverse[k]);
    Real w_grad_sq = 0, grad_dot_dx = 0;
    for (int i = 0; i < 4; ++i) {
      w_grad_sq += s.inv_mass[p[i]] * v.grad[i].squaredNorm();
      grad_dot_dx += v.grad[i].dot(s.x[p[i]] - s.x_start[p[i]]);
    }
    const Real dl = xpbd_delta_lambda(v.C, lambda[k], c.compliance[k], c.damping_time[k], s, w_grad_sq, grad_dot_dx);
    lambda[k] += dl;
    for (int i = 0; i < 4; ++i) s.x[p[i]] += s.inv_mass[p[i]] * dl * v.grad[i];
  });
}

}  // namespace moreau
