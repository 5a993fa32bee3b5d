#include "moreau/continuum/velocity_gradient.hpp"

#include <Eigen/SVD>

namespace moreau {

Mat3 kernel_correction(const WendlandKernel& kernel, std::span<const KernelNeighbor> neighbors, Real tolerance) {
  Mat3 M = Mat3::Zero();
  for (const KernelNeighbor& b : neighbors)
    M += b.volume * (-kernel.gradient_factor(b.offset.norm()) * b.offset) * b.offset.transpose();
  const Eigen::JacobiSVD<Mat3> svd(M, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Vec3 s = svd.singularValues();
  if (s[0] <= 0) return Mat3::Zero();  // no neighbour: no gradient
  Vec3 inverse = Vec3::Zero();
  for (int i = 0; i < 3; ++i)
    if (s[i] > tolerance * s[0]) inverse[i] = 1 / s[i];
  return svd.matrixV() * inverse.asDiagonal() * svd.matrixU().transpose();
}

Mat3 velocity_gradient(const WendlandKernel& kernel, const Mat3& correction, std::span<const KernelNeighbor> neighbors,
                       std::span<const Vec3> velocity_difference) {
  Mat3 gradient = Mat3::Zero();
  for (size_t b = 0; b < neighbors.size(); ++b)
    gradient += neighbors[b].volume * velocity_difference[b] *
                corrected_gradient(kernel, correction, neighbors[b].offset).transpose();
  return gradient;
}

}  // namespace moreau
