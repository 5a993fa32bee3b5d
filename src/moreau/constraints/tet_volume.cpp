#include "moreau/constraints/tet_volume.hpp"

#include <cmath>

#include "moreau/constraints/tet_kinematics.hpp"

namespace moreau {

void TetVolumeConstraints::add(const std::array<Index, 4>& tet, const std::array<Vec3, 4>& rest, Real volume_compliance,
                               Real tau, Index obj) {
  Mat3 Dm;
  Dm.col(0) = rest[1] - rest[0];
  Dm.col(1) = rest[2] - rest[0];
  Dm.col(2) = rest[3] - rest[0];
  particles.push_back(tet);
  rest_inverse.push_back(Dm.inverse());
  compliance.push_back(volume_compliance / (Dm.determinant() / 6.0));
  damping_time.push_back(tau);
  object.push_back(obj);
}

void TetVolumeConstraints::color(const std::vector<Real>& particle_inv_mass) {
  const auto permutation = color_constraints(particles, particle_inv_mass, batches);
  apply_permutation(particles, permutation);
  apply_permutation(rest_inverse, permutation);
  apply_permutation(compliance, permutation);
  apply_permutation(damping_time, permutation);
  apply_permutation(object, permutation);
}

TetVolumeValue evaluate_tet_volume(const std::array<Vec3, 4>& x, const Mat3& rest_inverse) {
  const Mat3 F = tet_deformation_gradient(x[0], x[1], x[2], x[3], rest_inverse);
  return {F.determinant() - 1, tet_vertex_gradients(cofactor(F), rest_inverse)};
}

void project_tet_volume(const TetVolumeConstraints& c, Real* lambda, const SubstepContext& s) {
  for_each_by_color(c.batches, [&](Index k) {
    const auto& p = c.particles[k];
    const TetVolumeValue v = evaluate_tet_volume({s.x[p[0]], s.x[p[1]], s.x[p[2]], s.x[p[3]]}, c.rest_inverse[k]);
    Real w_grad_sq = 0, grad_dot_dx = 0;
    for (int i = 0; i < 4; ++i) {
      w_grad_sq += s.inv_mass[p[i]] * v.grad[i].squaredNorm();
      grad_dot_dx += v.grad[i].dot(s.x[p[i]] - s.x_start[p[i]]);
    }
    const Real dl = xpbd_delta_lambda(v.C, lambda[k], c.compliance[k], c.damping_time[k], s, w_grad_sq, grad_dot_dx);
    lambda[k] += dl;
    for (int i = 0; i < 4; ++i) s.x[p[i]] += s.inv_mass[p[i]] * dl * v.grad[i];
  });
}

Real tet_volume_energy(const TetVolumeConstraints& c, const Vec3* x, Index object) {
  Real energy = 0;
  for (size_t k = 0; k < c.size(); ++k) {
    if ((object >= 0 && c.object[k] != object) || c.compliance[k] <= 0) continue;
    const auto& p = c.particles[k];
    const Real C = evaluate_tet_volume({x[p[0]], x[p[1]], x[p[2]], x[p[3]]}, c.rest_inverse[k]).C;
    energy += 0.5 * C * C / c.compliance[k];
  }
  return energy;
}

Real tet_volume_max_error(const TetVolumeConstraints& c, const Vec3* x, Index object) {
  Real error = 0;
  for (size_t k = 0; k < c.size(); ++k) {
    if (object >= 0 && c.object[k] != object) continue;
    const auto& p = c.particles[k];
    error = std::max(error, std::abs(evaluate_tet_volume({x[p[0]], x[p[1]], x[p[2]], x[p[3]]}, c.rest_inverse[k]).C));
  }
  return error;
}

}  // namespace moreau
