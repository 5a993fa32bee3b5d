#include "moreau/fem/solids/solid_element.hpp"

#include "moreau/fem/solids/mean_dilatation.hpp"
#include "moreau/fem/solids/solid_element_kernels.hpp"

namespace moreau {

Mat3 displacement_gradient(const Vec3* G, int nodes, int dim, const Real* u) {
  Mat3 H = Mat3::Zero();
  for (int a = 0; a < nodes; ++a)
    for (int k = 0; k < dim; ++k) H.row(k) += u[a * dim + k] * G[a].transpose();
  return H;
}

void solid_element(const HyperelasticMaterial& material, VolumeTreatment volume, const CellQuadrature& q, int dim,
                   const Real* u, bool with_tangent, ElementOutput& out) {
  if (volume == VolumeTreatment::mean_dilatation)
    return mean_dilatation_element(material, q, dim, u, with_tangent, out);
  start_output(q.nodes * dim, with_tangent, out);
  StrainMatrix B;
  for (int p = 0; p < q.points; ++p) {
    const Vec3* G = q.gradient + static_cast<size_t>(p) * q.nodes;
    const Real w = q.weight[p];
    const Mat3 H = displacement_gradient(G, q.nodes, dim, u);
    const Mat3 F = Mat3::Identity() + H;
    // det C = J^2 cannot see an inverted point (J < 0); W is defined for J > 0 only.
    if (!(F.determinant() > 0)) return mark_inverted(out);
    const HyperelasticResponse r = material.respond(green_lagrange_strain(H), with_tangent);
    if (!r.valid) return mark_inverted(out);
    out.energy += w * r.energy;
    strain_displacement(F, G, q.nodes, dim, B);
    out.force.noalias() += w * B.transpose() * r.stress;
    if (with_tangent) add_tangent(B, B, r.tangent, r.stress, G, q.nodes, dim, w, out.tangent);
  }
}

void solid_element_step(const HyperelasticMaterial& material, VolumeTreatment volume, const CellQuadrature& q,
                        int dim, const Real* u_n, const Real* u_next, StepRule rule, bool with_tangent,
                        ElementOutput& out) {
  if (volume == VolumeTreatment::mean_dilatation)
    return mean_dilatation_element_step(material, q, dim, u_n, u_next, rule, with_tangent, out);
  start_output(q.nodes * dim, with_tangent, out);
  StrainMatrix B, B_next;
  for (int p = 0; p < q.points; ++p) {
    const Vec3* G = q.gradient + static_cast<size_t>(p) * q.nodes;
    const Real w = q.weight[p];
    const Mat3 H0 = displacement_gradient(G, q.nodes, dim, u_n);
    const Mat3 H1 = displacement_gradient(G, q.nodes, dim, u_next);
    const Mat3 Fm = Mat3::Identity() + 0.5 * (H0 + H1);
    if (!((Mat3::Identity() + H1).determinant() > 0) || !(Fm.determinant() > 0)) return mark_inverted(out);
    const Mat3 E0 = green_lagrange_strain(H0), E1 = green_lagrange_strain(H1);
    strain_displacement(Fm, G, q.nodes, dim, B);
    if (rule == StepRule::midpoint) {
      const HyperelasticResponse r1 = material.respond(E1, false);
      const HyperelasticResponse r = material.respond(green_lagrange_strain(0.5 * (H0 + H1)), with_tangent);
      if (!r1.valid || !r.valid) return mark_inverted(out);
      out.energy += w * r1.energy;
      out.force.noalias() += w * B.transpose() * r.stress;
      if (with_tangent) add_tangent(B, B, r.tangent, r.stress, G, q.nodes, dim, 0.5 * w, out.tangent);
      continue;
    }
    const PointDiscreteGradient d = discrete_gradient(material, E0, E1, with_tangent);
    if (!d.valid) return mark_inverted(out);
    out.energy += w * d.energy;
    out.force.noalias() += w * B.transpose() * d.stress;
    if (!with_tangent) continue;
    // d E_avg / d u_next = B(F_next) / 2, and the correction depends on E1 = E(F_next) itself:
    // the tangent is not symmetric.
    strain_displacement(Mat3::Identity() + H1, G, q.nodes, dim, B_next);
    add_tangent(B, B_next, d.tangent, d.stress, G, q.nodes, dim, 0.5 * w, out.tangent);
  }
}

}  // namespace moreau
