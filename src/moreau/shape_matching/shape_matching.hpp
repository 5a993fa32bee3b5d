#pragma once
// Meshless deformation by shape matching (Mueller, Heidelberger, Teschner, Gross 2005,
// "Meshless Deformations Based on Shape Matching", sec. 3.3), with overlapping clusters.
//
// A cluster holds particles i with masses m_i and rest positions xbar_i. Its rest offsets are
// q_i = xbar_i - cbar, cbar = sum m_i xbar_i / M. At positions x, the best rigid fit of the rest
// shape is the rotation R of the polar decomposition of A = sum m_i (x_i - c) q_i^T about the
// current mass centre c = sum m_i x_i / M, and the goals are g_i = c + R q_i.
//
// As an XPBD constraint: the energy E = 1/2 sum m_i omega^2 |x_i - g_i|^2 (omega = 2 pi f, f the
// cluster's frequency: a particle of one cluster pulled off its goal oscillates at f; one in k
// overlapping clusters feels each, about sqrt(k) f) gives each particle the compliance
// 1/(m_i omega^2), so a substep's first projection moves every particle of the cluster by the same
// fraction of the way to its goal (solvers/xpbd/project_shape_matching.hpp has the multiplier):
//   x_i += s (g_i - x_i),   s = w_i / (w_i + 1/(m_i omega^2 h^2)) = omega^2 h^2 / (1 + omega^2 h^2),
// and s = 1 for a rigid cluster (f infinite). The same s for all keeps sum m_i (g_i - x_i) = 0
// (c is the mass centre of the goals too): the projection conserves linear momentum. It also
// conserves the angular momentum about c of the positions it corrects: with A = R S (S symmetric),
// sum m_i (x_i - c) x R q_i is the axial vector of R A^T - A R^T = R S R^T - (R S R^T)^T = 0.
#include <vector>

#include "moreau/math/types.hpp"

namespace moreau {

/// The clusters of every shape-matched object, in CSR form.
struct ShapeMatchClusters {
  std::vector<Index> offsets{0};  // cluster k: entries [offsets[k], offsets[k + 1])
  std::vector<Index> particle;    // per entry: a global particle index
  std::vector<Vec3> rest_offset;  // per entry: q_i = xbar_i - cbar, m
  std::vector<Real> mass;         // per entry: m_i, kg
  std::vector<Real> omega;        // per cluster: 2 pi f, rad/s; 0 for a rigid cluster
  std::vector<Index> object;      // per cluster: the owning object
  bool disjoint = true;           // no particle is in two clusters (clumps; objects of one cluster or apart ones)
  std::vector<char> member;       // per particle: in some cluster (to keep `disjoint`)

  Index size() const { return static_cast<Index>(offsets.size()) - 1; }
  bool empty() const { return size() == 0; }
  /// Adds a cluster of the particles `members` (at rest positions `rest`, masses `masses`, both
  /// indexed by global particle) with angular frequency omega (0: rigid).
  void add(const std::vector<Index>& members, const std::vector<Vec3>& rest, const std::vector<Real>& masses,
           Real omega, Index owner);
};

/// The rotation R of the polar decomposition A = R S (det R = +1; for a degenerate A, the
/// rotation of the nearest proper orthogonal matrix from its SVD).
Mat3 polar_rotation(const Mat3& A);

/// The best rigid fit of cluster k at positions x: its mass M, mass centre c, A = sum m_i (x_i - c)
/// q_i^T and A's rotation R.
struct ShapeMatchFit {
  Real mass = 0;
  Vec3 center = Vec3::Zero();
  Mat3 A = Mat3::Zero(), R = Mat3::Identity();
};
ShapeMatchFit fit_cluster(const ShapeMatchClusters& clusters, Index k, const Vec3* x);

/// Goals g_i of cluster k at positions x, written to goals[0 .. cluster size).
void shape_match_goals(const ShapeMatchClusters& clusters, Index k, const Vec3* x, Vec3* goals);

/// Elastic energy 1/2 sum m_i omega^2 |x_i - g_i|^2 of the compliant clusters of `object` (-1:
/// all), J; rigid clusters store none.
Real shape_match_energy(const ShapeMatchClusters& clusters, const Vec3* x, Index object);

}  // namespace moreau
