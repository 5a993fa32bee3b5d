#include "moreau/constraints/dihedral_bending.hpp"

#include <cmath>

namespace moreau {

void DihedralBendingConstraints::color(const std::vector<Real>& particle_inv_mass) {
  std::vector<std::array<Index, 4>> stencils;
  for (const auto& h : hinges) stencils.push_back({h.e0, h.e1, h.o0, h.o1});
  const auto permutation = color_constraints(stencils, particle_inv_mass, batches);
  apply_permutation_to_all(permutation, hinges, rest_angle, compliance, damping_time, object);
}

Real hinge_compliance_from_bending_stiffness(const Vec3& e0, const Vec3& e1, const Vec3& o0, const Vec3& o1,
                                             Real bending_stiffness) {
  const Vec3 e = e1 - e0;
  const Real area_sum = 0.5 * (e.cross(o0 - e0).norm() + (o1 - e0).cross(e).norm());
  return area_sum / (bending_stiffness * e.squaredNorm());
}

DihedralBendingConstraints::Rows DihedralBendingConstraints::rows(Index k, const Vec3* x) const {
  const Hinge& h = hinges[k];
  const DihedralValue v = evaluate_dihedral(x[h.e0], x[h.e1], x[h.o0], x[h.o1]);
  Rows r;
  r.particle = {h.e0, h.e1, h.o0, h.o1};
  r.C(0) = wrap_angle(v.theta - rest_angle[k]);
  for (int i = 0; i < 4; ++i) r.gradient[i] = v.grad[i].transpose();
  r.compliance(0, 0) = compliance[k];
  r.damping_time = damping_time[k];
  return r;
}

Real DihedralBendingConstraints::energy(const Vec3* x, Index of_object) const {
  Real energy = 0;
  for (size_t k = 0; k < size(); ++k) {
    if ((of_object >= 0 && object[k] != of_object) || compliance[k] <= 0) continue;
    const Hinge& h = hinges[k];
    const Real C = wrap_angle(evaluate_dihedral(x[h.e0], x[h.e1], x[h.o0], x[h.o1]).theta - rest_angle[k]);
    energy += 0.5 * C * C / compliance[k];
  }
  return energy;
}

Real DihedralBendingConstraints::max_error(const Vec3* x, Index of_object) const {
  Real error = 0;
  for (size_t k = 0; k < size(); ++k) {
    if (of_object >= 0 && object[k] != of_object) continue;
    const Hinge& h = hinges[k];
    error = std::max(error, std::abs(wrap_angle(evaluate_dihedral(x[h.e0], x[h.e1], x[h.o0], x[h.o1]).theta - rest_angle[k])));
  }
  return error;
}

}  // namespace moreau
