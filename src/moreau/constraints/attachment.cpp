#include "moreau/constraints/attachment.hpp"

namespace moreau {

void project_attachments(const AttachmentConstraints& c, Vec3* lambda, const SubstepContext& s) {
  const Index n = static_cast<Index>(c.size());
#pragma omp for schedule(static)
  for (Index k = 0; k < n; ++k) {
    const Index p = c.particle[k];
    const Real w = s.inv_mass[p];
    const Real alpha_tilde = c.compliance[k] * s.inv_h2;
    const Real gamma = c.damping_time[k] * s.inv_h;
    const Vec3 C = s.x[p] - c.target[k];
    const Real denominator = (1 + gamma) * w + alpha_tilde;
    if (denominator <= 0) continue;
    const Vec3 dl = (-C - alpha_tilde * lambda[k] - gamma * (s.x[p] - s.x_start[p])) / denominator;
    lambda[k] += dl;
    s.x[p] += w * dl;
  }
}

Real attachment_energy(const AttachmentConstraints& c, const Vec3* x, Index object) {
  Real energy = 0;
  for (size_t k = 0; k < c.size(); ++k)
    if ((object < 0 || c.object[k] == object) && c.compliance[k] > 0)
      energy += 0.5 * (x[c.particle[k]] - c.target[k]).squaredNorm() / c.compliance[k];
  return energy;
}

Real attachment_max_error(const AttachmentConstraints& c, const Vec3* x, Index object) {
  Real error = 0;
  for (size_t k = 0; k < c.size(); ++k)
    if (object < 0 || c.object[k] == object) error = std::max(error, (x[c.particle[k]] - c.target[k]).norm());
  return error;
}

}  // namespace moreau
