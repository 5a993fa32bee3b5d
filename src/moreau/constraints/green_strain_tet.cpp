#include "moreau/constraints/green_strain_tet.hpp"

#include <cmath>

#include "moreau/constraints/tet_kinematics.hpp"

namespace moreau {

namespace {

// Voigt order: rows 0-2 the normal strains, rows 3-5 the shears of the axis pairs (1,2), (0,2), (0,1).
constexpr int kShearPair[3][2] = {{1, 2}, {0, 2}, {0, 1}};

Mat3 deformation_gradient(const std::array<Index, 4>& p, const Vec3* x, const Mat3& rest_inverse) {
  return tet_deformation_gradient(x[p[0]], x[p[1]], x[p[2]], x[p[3]], rest_inverse);
}

GreenStrainTetConstraints::Rows::Vector voigt_strain(const Mat3& F) {
  const Mat3 E = 0.5 * (F.transpose() * F - Mat3::Identity());
  GreenStrainTetConstraints::Rows::Vector C;
  for (int j = 0; j < 3; ++j) C[j] = E(j, j);
  for (int s = 0; s < 3; ++s) C[3 + s] = 2 * E(kShearPair[s][0], kShearPair[s][1]);
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

GreenStrainTetConstraints::Rows GreenStrainTetConstraints::rows(Index k, const Vec3* x) const {
  const Mat3 F = deformation_gradient(particles[k], x, rest_inverse[k]);
  Rows r;
  r.particle = particles[k];
  r.C = voigt_strain(F);
  for (int row = 0; row < 6; ++row) {
    Mat3 dC_dF = Mat3::Zero();
    if (row < 3) {
      dC_dF.col(row) = F.col(row);
    } else {
      const int j = kShearPair[row - 3][0], l = kShearPair[row - 3][1];
      dC_dF.col(j) = F.col(l);
      dC_dF.col(l) = F.col(j);
    }
    const std::array<Vec3, 4> g = tet_vertex_gradients(dC_dF, rest_inverse[k]);
    for (int i = 0; i < 4; ++i) r.gradient[i].row(row) = g[i].transpose();
  }
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
