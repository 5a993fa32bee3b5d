#include "moreau/constraints/neo_hookean_green_strain.hpp"

#include <Eigen/Eigenvalues>

#include "moreau/constraints/tet_kinematics.hpp"

namespace moreau {

GreenStrainTetConstraints::Rows neo_hookean_green_strain_rows(const NeoHookeanTetConstraints& family, Index k,
                                                              const Vec3* x) {
  using Rows = GreenStrainTetConstraints::Rows;
  const NeoHookeanElement& e = family.elements[k];
  const std::array<Index, 4>& p = e.particles;
  const Mat3 F = tet_deformation_gradient(x[p[0]], x[p[1]], x[p[2]], x[p[3]], family.rest_inverse[k]);
  Rows r = green_strain_rows(p, F, family.rest_inverse[k]);

  // The moduli times the rest volume: mu V = 1/alpha_D, lambda V = 1/alpha_H.
  const Real mu_V = 1 / e.compliance_D, lambda_V = 1 / e.compliance_H;
  const Mat3 C = F.transpose() * F;
  const Real J = F.determinant();
  // A degenerate element (J = 0) has no C^-1; it takes the rest tangent and the stress mu I.
  const bool degenerate = std::abs(J) < 1e-12;
  const Mat3 Cinv = degenerate ? Mat3::Identity() : Mat3(C.inverse());
  const Real pressure_V = degenerate ? 0 : lambda_V * (J - e.gamma) * J;
  const Real volumetric_V = degenerate ? lambda_V - mu_V : lambda_V * (2 * J - e.gamma) * J;
  const Real deviatoric_V = degenerate ? -mu_V : pressure_V;

  Rows::Vector stress_V;  // V S in Voigt order
  Rows::Compliance tangent_V;  // V DD in Voigt order
  for (int a = 0; a < 6; ++a) {
    const int i = kVoigtPair[a][0], j = kVoigtPair[a][1];
    stress_V[a] = (i == j ? mu_V : 0) + pressure_V * Cinv(i, j);
    for (int b = 0; b < 6; ++b) {
      const int k2 = kVoigtPair[b][0], l = kVoigtPair[b][1];
      tangent_V(a, b) = volumetric_V * Cinv(i, j) * Cinv(k2, l) -
                        deviatoric_V * (Cinv(i, k2) * Cinv(j, l) + Cinv(i, l) * Cinv(j, k2));
    }
  }
  Eigen::SelfAdjointEigenSolver<Rows::Compliance> eigen(tangent_V);
  // The rest tangent's smallest eigenvalue: mu (the shears) or the bulk modulus 3K = 3 lambda_Lame
  // + 2 mu = 3 lambda - mu, which is the smaller for nu < -1/4.
  const Real rest_smallest = std::min(mu_V, 3 * lambda_V - mu_V);
  const Rows::Vector stiffness = eigen.eigenvalues().cwiseMax(rest_smallest);
  const Rows::Compliance& Q = eigen.eigenvectors();
  r.compliance = Q * stiffness.cwiseInverse().asDiagonal() * Q.transpose();
  r.C = r.compliance * stress_V;
  r.damping_time = e.damping_time;
  return r;
}

}  // namespace moreau
