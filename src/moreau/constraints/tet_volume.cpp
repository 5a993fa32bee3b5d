#include "moreau/constraints/tet_volume.hpp"

#include <cmath>


namespace moreau {

void TetVolumeConstraints::add(const std::array<Index, 4>& tet, const std::array<Vec3, 4>& rest, Real volume_compliance,
                               Real tau, Index obj) {
  const Mat3 Dm = tet_edge_matrix(rest);
  particles.push_back(tet);
  rest_inverse.push_back(Dm.inverse());
  compliance.push_back(volume_compliance / (Dm.determinant() / 6.0));
  damping_time.push_back(tau);
  object.push_back(obj);
}

void TetVolumeConstraints::color(const std::vector<Real>& particle_inv_mass) {
  const auto permutation = color_constraints(particles, particle_inv_mass, batches);
  apply_permutation_to_all(permutation, particles, rest_inverse, compliance, damping_time, object);
}

TetVolumeConstraints::Rows TetVolumeConstraints::rows(Index k, const Vec3* x) const {
  const auto& p = particles[k];
  const TetVolumeValue v = evaluate_tet_volume({x[p[0]], x[p[1]], x[p[2]], x[p[3]]}, rest_inverse[k]);
  Rows r;
  r.particle = p;
  r.C(0) = v.C;
  for (int i = 0; i < 4; ++i) r.gradient[i] = v.grad[i].transpose();
  r.compliance(0, 0) = compliance[k];
  r.damping_time = damping_time[k];
  return r;
}

Real TetVolumeConstraints::energy(const Vec3* x, Index of_object) const {
  Real energy = 0;
  for (size_t k = 0; k < size(); ++k) {
    if ((of_object >= 0 && object[k] != of_object) || compliance[k] <= 0) continue;
    const auto& p = particles[k];
    const Real C = evaluate_tet_volume({x[p[0]], x[p[1]], x[p[2]], x[p[3]]}, rest_inverse[k]).C;
    energy += 0.5 * C * C / compliance[k];
  }
  return energy;
}

Real TetVolumeConstraints::max_error(const Vec3* x, Index of_object) const {
  Real error = 0;
  for (size_t k = 0; k < size(); ++k) {
    if (of_object >= 0 && object[k] != of_object) continue;
    const auto& p = particles[k];
    error = std::max(error, std::abs(evaluate_tet_volume({x[p[0]], x[p[1]], x[p[2]], x[p[3]]}, rest_inverse[k]).C));
  }
  return error;
}

}  // namespace moreau
