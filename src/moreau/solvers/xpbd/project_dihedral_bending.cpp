// XPBD projection of dihedral bending: the scalar update on the wrapped angle.
// A closed form of the generic row projection (project_rows.hpp) for this family's rows; the
// test XpbdKernels.AgreeWithTheGenericRowProjection holds the two together.
#include "moreau/solvers/xpbd/particle_projections.hpp"

#include <cmath>

namespace moreau {

void xpbd_project(const DihedralBendingConstraints& c, Real* lambda, const SubstepContext& s) {
  for_each_by_color(c.batches, [&](Index k) {
    const Hinge& h = c.hinges[k];
    const std::array<Index, 4> p{h.e0, h.e1, h.o0, h.o1};
    const DihedralValue v = evaluate_dihedral(s.x[p[0]], s.x[p[1]], s.x[p[2]], s.x[p[3]]);
    const std::array<Real, 4> w{s.inv_mass[p[0]], s.inv_mass[p[1]], s.inv_mass[p[2]], s.inv_mass[p[3]]};
    Real w_grad_sq = 0;
    for (int i = 0; i < 4; ++i) w_grad_sq += w[i] * v.grad[i].squaredNorm();
    const Real tau = c.damping_time[k];
    Real grad_dot_dx = 0;
    if (tau > 0)
      for (int i = 0; i < 4; ++i) grad_dot_dx += v.grad[i].dot(s.x[p[i]] - s.x_start[p[i]]);
    const Real C = wrap_angle(v.theta - c.rest_angle[k]);
    const Real dl = xpbd_delta_lambda(C, lambda[k], c.compliance[k], tau, s, w_grad_sq, grad_dot_dx);
    lambda[k] += dl;
    for (int i = 0; i < 4; ++i) s.x[p[i]] += (w[i] * dl) * v.grad[i];
  });
}

}  // namespace moreau
