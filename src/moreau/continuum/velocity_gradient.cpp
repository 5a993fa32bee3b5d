#include "moreau/continuum/velocity_gradient.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>

namespace moreau {

Mat3 kernel_correction(const WendlandKernel& kernel, std::span<const KernelNeighbor> neighbors, Real tolerance) {
  Mat3 M = Mat3::Zero();
  for (const KernelNeighbor& b : neighbors)
    M += b.volume * (-kernel.gradient_factor(b.offset.norm()) * b.offset) * b.offset.transpose();
  // M = sum V_b (-W'(|x|)/|x|) x x^T is symmetric and positive semi-definite: its singular values
  // are its eigenvalues, from Eigen's closed-form 3 x 3 solver. Where they span three directions
  // (nearly always) the inverse is the closed-form one; otherwise the pseudo-inverse drops the
  // directions below the tolerance.
  Eigen::SelfAdjointEigenSolver<Mat3> eigen;
  eigen.computeDirect(M, Eigen::EigenvaluesOnly);
  const Vec3 s = eigen.eigenvalues();  // ascending
  if (!(s[2] > 0)) return Mat3::Zero();  // no neighbour: no gradient
  if (s[0] > tolerance * s[2]) return M.inverse();
  eigen.computeDirect(M);
  Vec3 inverse = Vec3::Zero();
  for (int i = 0; i < 3; ++i)
    if (eigen.eigenvalues()[i] > tolerance * s[2]) inverse[i] = 1 / eigen.eigenvalues()[i];
  return eigen.eigenvectors() * inverse.asDiagonal() * eigen.eigenvectors().transpose();
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
