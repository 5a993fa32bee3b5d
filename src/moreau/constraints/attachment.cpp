#include "moreau/constraints/attachment.hpp"

namespace moreau {

void AttachmentConstraints::color(const std::vector<Real>&) {
  batches.offsets = {0, static_cast<Index>(size())};
}

AttachmentConstraints::Rows AttachmentConstraints::rows(Index k, const Vec3* x) const {
  Rows r;
  r.particle = {particle[k]};
  r.C = x[particle[k]] - target[k];
  r.gradient = {Mat3::Identity()};
  r.compliance = compliance[k] * Mat3::Identity();
  r.damping_time = damping_time[k];
  return r;
}

Real AttachmentConstraints::energy(const Vec3* x, Index of_object) const {
  Real energy = 0;
  for (size_t k = 0; k < size(); ++k)
    if ((of_object < 0 || object[k] == of_object) && compliance[k] > 0)
      energy += 0.5 * (x[particle[k]] - target[k]).squaredNorm() / compliance[k];
  return energy;
}

Real AttachmentConstraints::max_error(const Vec3* x, Index of_object) const {
  Real error = 0;
  for (size_t k = 0; k < size(); ++k)
    if (of_object < 0 || object[k] == of_object) error = std::max(error, (x[particle[k]] - target[k]).norm());
  return error;
}

}  // namespace moreau
