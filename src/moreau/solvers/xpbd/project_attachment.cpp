// XPBD projection of attachments: grad C = I, one colour (each particle is pinned at most once).
// A closed form of the generic row projection (project_rows.hpp) for this family's rows; the
// test XpbdKernels.AgreeWithTheGenericRowProjection holds the two together.
#include "moreau/solvers/xpbd/particle_projections.hpp"

namespace moreau {

void xpbd_project(const AttachmentConstraints& c, Vec3* lambda, const SubstepContext& s) {
  for_each_by_color(c.batches, [&](Index k) {
    const Index p = c.particle[k];
    const Real w = s.inv_mass[p];
    const Real alpha_tilde = c.compliance[k] * s.inv_h2;
    const Real gamma = c.damping_time[k] * s.inv_h;
    const Vec3 C = s.x[p] - c.target[k];
    const Real denominator = (1 + gamma) * w + alpha_tilde;
    if (denominator <= 0) return;
    const Vec3 dl = (-C - alpha_tilde * lambda[k] - gamma * (s.x[p] - s.x_start[p])) / denominator;
    lambda[k] += dl;
    s.x[p] += w * dl;
  });
}

}  // namespace moreau
