// XPBD projection of isometric bending: with grad_i C = K_i I the 3x3 system is a multiple of I.
// A closed form of the generic row projection (project_rows.hpp) for this family's rows; the
// test XpbdKernels.AgreeWithTheGenericRowProjection holds the two together.
#include "moreau/solvers/xpbd/particle_projections.hpp"

namespace moreau {

void xpbd_project(const IsometricBendingConstraints& c, Vec3* lambda, const SubstepContext& s) {
  for_each_by_color(c.batches, [&](Index k) {
    const IsometricHinge& h = c.hinges[k];
    const auto& p = h.particles;
    const auto& K = h.weight;
    const std::array<Real, 4> w{s.inv_mass[p[0]], s.inv_mass[p[1]], s.inv_mass[p[2]], s.inv_mass[p[3]]};
    const Vec3 C = isometric_bending_value(h, s.x);
    // XPBD with grad_i C = K_i I: the 3x3 system matrix is ((1+g) sum_i w_i K_i^2 + alpha~) I.
    const Real alpha_tilde = h.compliance * s.inv_h2;
    const Real g = h.damping_time * s.inv_h;
    Vec3 rhs = -(C + alpha_tilde * lambda[k]);
    if (g > 0) {
      Vec3 J_dx = Vec3::Zero();
      for (int i = 0; i < 4; ++i) J_dx += K[i] * (s.x[p[i]] - s.x_start[p[i]]);
      rhs -= g * J_dx;
    }
    const Real denominator =
        (1 + g) * (w[0] * K[0] * K[0] + w[1] * K[1] * K[1] + w[2] * K[2] * K[2] + w[3] * K[3] * K[3]) + alpha_tilde;
    if (!(denominator > 0)) return;
    const Vec3 dl = rhs * (1 / denominator);
    lambda[k] += dl;
    for (int i = 0; i < 4; ++i) s.x[p[i]] += (w[i] * K[i]) * dl;
  });
}

}  // namespace moreau
