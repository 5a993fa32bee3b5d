// XPBD projection of triangle strain: the 3x3 block update with the full compliance matrix.
// A closed form of the generic row projection (project_rows.hpp) for this family's rows; the
// test XpbdKernels.AgreeWithTheGenericRowProjection holds the two together.
#include "moreau/solvers/xpbd/particle_projections.hpp"

#include <Eigen/Dense>

namespace moreau {

void xpbd_project(const TriangleStrainConstraints& c, Vec3* lambda, const SubstepContext& s) {
  for_each_by_color(c.batches, [&](Index k) {
    const auto& p = c.particles[k];
    const TriangleStrainValue v = evaluate_triangle_strain(s.x[p[0]], s.x[p[1]], s.x[p[2]], c.rest_inverse[k]);
    // Block XPBD update: [(1+gamma) J W J^T + alpha~] dlambda = -(C + alpha~ lambda + gamma J dx).
    Mat3 JWJt = Mat3::Zero();
    Vec3 J_dx = Vec3::Zero();
    for (int i = 0; i < 3; ++i) {
      JWJt += s.inv_mass[p[i]] * v.grad[i] * v.grad[i].transpose();
      J_dx += v.grad[i] * (s.x[p[i]] - s.x_start[p[i]]);
    }
    const Mat3 alpha_tilde = c.compliance[k] * s.inv_h2;
    const Real gamma = c.damping_time[k] * s.inv_h;
    const Mat3 A = (1 + gamma) * JWJt + alpha_tilde;
    const Vec3 rhs = -(v.C + alpha_tilde * lambda[k] + gamma * J_dx);
    const Vec3 dl = A.ldlt().solve(rhs);
    if (!dl.allFinite()) return;
    lambda[k] += dl;
    for (int i = 0; i < 3; ++i) s.x[p[i]] += s.inv_mass[p[i]] * (v.grad[i].transpose() * dl);
  });
}

}  // namespace moreau
