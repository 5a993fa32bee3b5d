#include "moreau/solvers/nmd/shape_match_rows.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>

namespace moreau {

void add_shape_match_rows(const Model& model, const State& state, const VelocitySpace& space, Real h, NmdBlockInput& in,
                          NmdSystem& system, std::vector<Vec3>& memory) {
  const ShapeMatchClusters& clusters = model.shape_matching;
  memory.resize(clusters.particle.size(), Vec3::Zero());
  thread_local std::vector<Vec3> p;     // R q_j of each member (kept from step to step: no allocation)
  thread_local std::vector<Mat3> turn;  // m_j K^-1 [p_j]x: how member j's velocity turns the fit
  for (Index k = 0; k < clusters.size(); ++k) {
    const Index begin = clusters.offsets[k], end = clusters.offsets[k + 1];
    if (state.sleep.cluster_asleep(clusters.particle[begin])) continue;  // a sleeping clump
    const int n = static_cast<int>(end - begin);
    const ShapeMatchFit fit = fit_cluster(clusters, k, state.position.data());
    const Real total = fit.mass;
    const Vec3& center = fit.center;
    const Mat3& R = fit.R;
    Mat3 S = fit.A * R.transpose();
    S = 0.5 * (S + S.transpose());  // symmetric up to rounding
    // K's pseudo-inverse: a cluster on a line (a clump's pair) has no inertia about that line, and
    // turning about it moves nothing; a fit turned inside out (K not positive) keeps its positive part.
    const Eigen::SelfAdjointEigenSolver<Mat3> eigen(S.trace() * Mat3::Identity() - S);
    const Real largest = eigen.eigenvalues().cwiseAbs().maxCoeff();
    Mat3 K_inverse = Mat3::Zero();
    for (int a = 0; a < 3; ++a)
      if (eigen.eigenvalues()[a] > 1e-9 * largest)
        K_inverse += eigen.eigenvectors().col(a) * eigen.eigenvectors().col(a).transpose() / eigen.eigenvalues()[a];
    p.resize(n);
    turn.resize(n);
    for (int j = 0; j < n; ++j) {
      p[j] = R * clusters.rest_offset[begin + j];
      turn[j] = clusters.mass[begin + j] * K_inverse * cross_matrix(p[j]);
    }
    const Real omega2 = clusters.omega[k] * clusters.omega[k];
    for (int i = 0; i < n; ++i) {
      const Index entry = begin + i, particle = clusters.particle[entry];
      if (model.particle_inv_mass[particle] <= 0) continue;
      in.resize(3, n);
      const Mat3 arm = cross_matrix(state.position[particle] - center);
      for (int j = 0; j < n; ++j) {
        in.end[j] = space.particle_end(clusters.particle[begin + j]);  // three loads: cheaper than a copy
        Mat3 J = arm * turn[j];
        J.diagonal().array() -= clusters.mass[begin + j] / total;
        if (j == i) J.diagonal().array() += 1;
        for (int r = 0; r < 3; ++r)
          for (int c = 0; c < 3; ++c) in.at(r, j)[c] = J(r, c);
      }
      in.C = state.position[particle] - center - p[i];
      if (omega2 > 0) in.compliance.diagonal().setConstant(1 / (clusters.mass[entry] * omega2));
      in.memory = memory[entry].data();
      in.memory_rows = 3;
      system.add(in, space, h, model.settings.nmd);
    }
  }
}

}  // namespace moreau
