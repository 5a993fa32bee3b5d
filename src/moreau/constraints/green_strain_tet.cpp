#include "moreau/constraints/green_strain_tet.hpp"

#include <cmath>

#include "moreau/constraints/tet_kinematics.hpp"

namespace moreau {

namespace {

Mat3 deformation_gradient(const std::array<Index, 4>& p, const Vec3* x, const Mat3& rest_inverse) {
  return tet_deformation_gradient(x[p[0]], x[p[1]], x[p[2]], x[p[3]], rest_inverse);
}

GreenStrainTetConstraints::Rows::Vector voigt_strain(const Mat3& F) {
  const Mat3 E = 0.5 * (F.transpose() * F - Mat3::Identity());
  GreenStrainTetConstraints::Rows::Vector C;
  for (int row = 0; row < 6; ++row) {
    const int j = kVoigtPair[row][0], k = kVoigtPair[row][1];
    C[row] = j == k ? E(j, j) : 2 * E(j, k);  // engineering shears
  }
  return C;
}

}  // namespace

void GreenStrainTetConstraints::add(const std::array<Index, 4>& tet, const std::array<Vec3, 4>& rest,
                                    Real youngs_modulus, Real poisson_ratio, Real tau, Index obj) {
  const Mat3 Dm = tet_edge_matrix(rest);
  const Real volume = Dm.determinant() / 6;
  const Real mu = youngs_modulus / (2 * (1 + poisson_ratio));
  const Real lambda = youngs_modulus * poisson_ratio / ((1 + poisson_ratio) * (1 - 2 * poisson_ratio));
  Rows::Compliance D = Rows::Compliance::Zero();
  D.topLeftCorner<3, 3>().setConstant(lambda);
  for (int j = 0; j < 3; ++j) D(j, j) += 2 * mu;
  for (int s = 3; s < 6; ++s) D(s, s) = mu;
  particles.push_back(tet);
  rest_inverse.push_back(Dm.inverse());
  compliance.push_back((volume * D).inverse());
  damping_time.push_back(tau);
  object.push_back(obj);
}

void GreenStrainTetConstraints::color(const std::vector<Real>& particle_inv_mass) {
  const auto permutation = color_constraints(particles, particle_inv_mass, batches);
  apply_permutation_to_all(permutation, particles, rest_inverse, compliance, damping_time, object);
}

GreenStrainTetConstraints::Rows green_strain_rows(const std::array<Index, 4>& particles, const Mat3& F,
                                                  const Mat3& rest_inverse) {
  GreenStrainTetConstraints::Rows r;
  r.particle = particles;
  r.C = voigt_strain(F);
  for (int row = 0; row < 6; ++row) {
    const int j = kVoigtPair[row][0], l = kVoigtPair[row][1];
    Mat3 dC_dF = Mat3::Zero();
    if (j == l) {
      dC_dF.col(j) = F.col(j);
    } else {
      dC_dF.col(j) = F.col(l);
      dC_dF.col(l) = F.col(j);
    }
    const std::array<Vec3, 4> g = tet_vertex_gradients(dC_dF, rest_inverse);
    for (int i = 0; i < 4; ++i) r.gradient[i].row(row) = g[i].transpose();
  }
  return r;
}

GreenStrainTetConstraints::Rows GreenStrainTetConstraints::rows(Index k, const Vec3* x) const {
  Rows r = green_strain_rows(particles[k], deformation_gradient(particles[k], x, rest_inverse[k]), rest_inverse[k]);
  r.compliance = compliance[k];
  r.damping_time = damping_time[k];
  return r;
}

Real GreenStrainTetConstraints::energy(const Vec3* x, Index of_object) const {
  Real energy = 0;
  for (size_t k = 0; k < size(); ++k) {
    if (of_object >= 0 && object[k] != of_object) continue;
    const Rows::Vector C = voigt_strain(deformation_gradient(particles[k], x, rest_inverse[k]));
    energy += 0.5 * C.dot(compliance[k].ldlt().solve(C));
  }
  return energy;
}

Real GreenStrainTetConstraints::max_error(const Vec3* x, Index of_object) const {
  Real error = 0;
  for (size_t k = 0; k < size(); ++k) {
    if (of_object >= 0 && object[k] != of_object) continue;
    Rows::Vector C = voigt_strain(deformation_gradient(particles[k], x, rest_inverse[k]));
    C.tail<3>() *= 0.5;
    error = std::max(error, C.cwiseAbs().maxCoeff());
  }
  return error;
}

}  // namespace moreau
