#include "moreau/constraints/dihedral_bending.hpp"

#include <cmath>

namespace moreau {

void DihedralBendingConstraints::color(const std::vector<Real>& particle_inv_mass) {
  std::vector<std::array<Index, 4>> stencils;
  for (const auto& h : hinges) stencils.push_back({h.e0, h.e1, h.o0, h.o1});
  const auto permutation = color_constraints(stencils, particle_inv_mass, batches);
  apply_permutation(hinges, permutation);
  apply_permutation(rest_angle, permutation);
  apply_permutation(compliance, permutation);
  apply_permutation(damping_time, permutation);
  apply_permutation(object, permutation);
}

DihedralValue evaluate_dihedral(const Vec3& e0, const Vec3& e1, const Vec3& o0, const Vec3& o1) {
  DihedralValue v{0, {Vec3::Zero(), Vec3::Zero(), Vec3::Zero(), Vec3::Zero()}};
  const Vec3 e = e1 - e0;
  const Real l2 = e.squaredNorm();
  const Vec3 nA = e.cross(o0 - e0);
  const Vec3 nB = (o1 - e0).cross(e);
  const Real nA2 = nA.squaredNorm(), nB2 = nB.squaredNorm();
  if (l2 <= 0 || nA2 <= 0 || nB2 <= 0) return v;  // degenerate hinge: no bending direction
  const Real l = std::sqrt(l2), inv_l = 1 / l;
  // atan2 is invariant to scaling both arguments by |nA||nB| > 0, so the normals need no normalizing.
  v.theta = std::atan2(nA.cross(nB).dot(e) * inv_l, nA.dot(nB));
  const Vec3 gA = nA * (1 / nA2), gB = nB * (1 / nB2);
  v.grad[2] = -l * gA;
  v.grad[3] = -l * gB;
  // (o - e1).e = (o - e0).e - l^2
  const Real sA = (o0 - e0).dot(e) * inv_l, sB = (o1 - e0).dot(e) * inv_l;
  v.grad[0] = (l - sA) * gA + (l - sB) * gB;
  v.grad[1] = sA * gA + sB * gB;
  return v;
}

Real hinge_compliance_from_bending_stiffness(const Vec3& e0, const Vec3& e1, const Vec3& o0, const Vec3& o1,
                                             Real bending_stiffness) {
  const Vec3 e = e1 - e0;
  const Real area_sum = 0.5 * (e.cross(o0 - e0).norm() + (o1 - e0).cross(e).norm());
  return area_sum / (bending_stiffness * e.squaredNorm());
}

namespace {
// Wraps an angle difference to (-pi, pi] so a hinge never takes the long way round.
Real wrap_angle(Real a) {
  while (a > kPi) a -= 2 * kPi;
  while (a <= -kPi) a += 2 * kPi;
  return a;
}
}  // namespace

void project_dihedral_bending(const DihedralBendingConstraints& c, Real* lambda, const SubstepContext& s) {
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

Real dihedral_bending_energy(const DihedralBendingConstraints& c, const Vec3* x, Index object) {
  Real energy = 0;
  for (size_t k = 0; k < c.size(); ++k) {
    if ((object >= 0 && c.object[k] != object) || c.compliance[k] <= 0) continue;
    const Hinge& h = c.hinges[k];
    const Real C = wrap_angle(evaluate_dihedral(x[h.e0], x[h.e1], x[h.o0], x[h.o1]).theta - c.rest_angle[k]);
    energy += 0.5 * C * C / c.compliance[k];
  }
  return energy;
}

Real dihedral_bending_max_error(const DihedralBendingConstraints& c, const Vec3* x, Index object) {
  Real error = 0;
  for (size_t k = 0; k < c.size(); ++k) {
    if (object >= 0 && c.object[k] != object) continue;
    const Hinge& h = c.hinges[k];
    error = std::max(error, std::abs(wrap_angle(evaluate_dihedral(x[h.e0], x[h.e1], x[h.o0], x[h.o1]).theta - c.rest_angle[k])));
  }
  return error;
}

}  // namespace moreau
