#include "moreau/shape_matching/shape_matching.hpp"

#include <Eigen/SVD>

namespace moreau {

void ShapeMatchClusters::add(const std::vector<Index>& members, const std::vector<Vec3>& rest,
                             const std::vector<Real>& masses, Real cluster_omega, Index owner) {
  Real total = 0;
  Vec3 center = Vec3::Zero();
  for (Index p : members) total += masses[p], center += masses[p] * rest[p];
  center /= total;
  for (Index p : members) {
    particle.push_back(p);
    rest_offset.push_back(rest[p] - center);
    mass.push_back(masses[p]);
  }
  offsets.push_back(static_cast<Index>(particle.size()));
  omega.push_back(cluster_omega);
  object.push_back(owner);
}

Mat3 polar_rotation(const Mat3& A) {
  const Eigen::JacobiSVD<Mat3> svd(A, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Mat3 U = svd.matrixU();
  const Mat3& V = svd.matrixV();
  // A reflection (det < 0) flips the axis of the smallest singular value.
  if ((U * V.transpose()).determinant() < 0) U.col(2) = -U.col(2);
  return U * V.transpose();
}

void shape_match_goals(const ShapeMatchClusters& clusters, Index k, const Vec3* x, Vec3* goals) {
  const Index begin = clusters.offsets[k], end = clusters.offsets[k + 1];
  Real total = 0;
  Vec3 center = Vec3::Zero();
  for (Index e = begin; e < end; ++e) total += clusters.mass[e], center += clusters.mass[e] * x[clusters.particle[e]];
  center /= total;
  Mat3 A = Mat3::Zero();
  for (Index e = begin; e < end; ++e)
    A += clusters.mass[e] * (x[clusters.particle[e]] - center) * clusters.rest_offset[e].transpose();
  const Mat3 R = polar_rotation(A);
  for (Index e = begin; e < end; ++e) goals[e - begin] = center + R * clusters.rest_offset[e];
}

}  // namespace moreau
