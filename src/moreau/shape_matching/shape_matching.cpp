#include "moreau/shape_matching/shape_matching.hpp"

#include <Eigen/SVD>
#include <vector>

namespace moreau {

void ShapeMatchClusters::add(const std::vector<Index>& members, const std::vector<Vec3>& rest,
                             const std::vector<Real>& masses, Real cluster_omega, Index owner) {
  Real total = 0;
  Vec3 center = Vec3::Zero();
  for (Index p : members) total += masses[p], center += masses[p] * rest[p];
  center /= total;
  for (Index p : members) {
    if (static_cast<Index>(member.size()) <= p) member.resize(p + 1, 0);
    disjoint = disjoint && !member[p];
    member[p] = 1;
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

ShapeMatchFit fit_cluster(const ShapeMatchClusters& clusters, Index k, const Vec3* x) {
  const Index begin = clusters.offsets[k], end = clusters.offsets[k + 1];
  ShapeMatchFit fit;
  for (Index e = begin; e < end; ++e) {
    fit.mass += clusters.mass[e];
    fit.center += clusters.mass[e] * x[clusters.particle[e]];
  }
  fit.center /= fit.mass;
  for (Index e = begin; e < end; ++e)
    fit.A += clusters.mass[e] * (x[clusters.particle[e]] - fit.center) * clusters.rest_offset[e].transpose();
  fit.R = polar_rotation(fit.A);
  return fit;
}

void shape_match_goals(const ShapeMatchClusters& clusters, Index k, const Vec3* x, Vec3* goals) {
  const ShapeMatchFit fit = fit_cluster(clusters, k, x);
  for (Index e = clusters.offsets[k]; e < clusters.offsets[k + 1]; ++e)
    goals[e - clusters.offsets[k]] = fit.center + fit.R * clusters.rest_offset[e];
}

Real shape_match_energy(const ShapeMatchClusters& clusters, const Vec3* x, Index object) {
  Real energy = 0;
  std::vector<Vec3> goals;
  for (Index k = 0; k < clusters.size(); ++k) {
    if (clusters.omega[k] <= 0 || (object >= 0 && clusters.object[k] != object)) continue;
    const Index begin = clusters.offsets[k], end = clusters.offsets[k + 1];
    goals.resize(end - begin);
    shape_match_goals(clusters, k, x, goals.data());
    const Real w2 = clusters.omega[k] * clusters.omega[k];
    for (Index e = begin; e < end; ++e)
      energy += 0.5 * clusters.mass[e] * w2 * (x[clusters.particle[e]] - goals[e - begin]).squaredNorm();
  }
  return energy;
}

}  // namespace moreau
