#include "moreau/constraints/triangle_strain.hpp"

#include <Eigen/Dense>

namespace moreau {

void TriangleStrainConstraints::add(const std::array<Index, 3>& tri, const Vec3& x0, const Vec3& x1, const Vec3& x2,
                                    Real youngs_modulus, Real poisson_ratio, Real thickness, Real tau, Index obj) {
  // Orthonormal rest basis: u along the first edge, v in the triangle plane.
  const Vec3 e1 = x1 - x0, e2 = x2 - x0;
  const Vec3 u = e1.normalized();
  const Vec3 v = (e2 - e2.dot(u) * u).normalized();
  Mat2 Dm;
  Dm << e1.dot(u), e2.dot(u), e1.dot(v), e2.dot(v);
  const Real area = 0.5 * std::abs(Dm.determinant());
  const Real mu = youngs_modulus / (2 * (1 + poisson_ratio));
  const Real lambda_ps = youngs_modulus * poisson_ratio / (1 - poisson_ratio * poisson_ratio);
  Mat3 K;
  K << lambda_ps + 2 * mu, lambda_ps, 0, lambda_ps, lambda_ps + 2 * mu, 0, 0, 0, mu;
  particles.push_back(tri);
  rest_inverse.push_back(Dm.inverse());
  compliance.push_back((area * thickness * K).inverse());
  damping_time.push_back(tau);
  object.push_back(obj);
}

void TriangleStrainConstraints::color(const std::vector<Real>& particle_inv_mass) {
  std::vector<std::array<Index, 4>> stencils;
  for (const auto& t : particles) stencils.push_back({t[0], t[1], t[2], -1});
  const auto permutation = color_constraints(stencils, particle_inv_mass, batches);
  apply_permutation_to_all(permutation, particles, rest_inverse, compliance, damping_time, object);
}

TriangleStrainConstraints::Rows TriangleStrainConstraints::rows(Index k, const Vec3* x) const {
  const auto& p = particles[k];
  const TriangleStrainValue v = evaluate_triangle_strain(x[p[0]], x[p[1]], x[p[2]], rest_inverse[k]);
  Rows r;
  r.particle = p;
  r.C = v.C;
  r.gradient = v.grad;
  r.compliance = compliance[k];
  r.damping_time = damping_time[k];
  return r;
}

Real TriangleStrainConstraints::energy(const Vec3* x, Index of_object) const {
  Real energy = 0;
  for (size_t k = 0; k < size(); ++k) {
    if (of_object >= 0 && object[k] != of_object) continue;
    const auto& p = particles[k];
    const Vec3 C = evaluate_triangle_strain(x[p[0]], x[p[1]], x[p[2]], rest_inverse[k]).C;
    energy += 0.5 * C.dot(compliance[k].ldlt().solve(C));
  }
  return energy;
}

Real TriangleStrainConstraints::max_error(const Vec3* x, Index of_object) const {
  Real error = 0;
  for (size_t k = 0; k < size(); ++k) {
    if (of_object >= 0 && object[k] != of_object) continue;
    const auto& p = particles[k];
    error = std::max(error, evaluate_triangle_strain(x[p[0]], x[p[1]], x[p[2]], rest_inverse[k]).C.cwiseAbs().maxCoeff());
  }
  return error;
}

}  // namespace moreau
