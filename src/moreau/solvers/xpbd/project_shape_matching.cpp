#include "moreau/solvers/xpbd/project_shape_matching.hpp"

#include <vector>

#include "moreau/model/model.hpp"
#include "moreau/sleeping/grain_sleep.hpp"

namespace moreau {

namespace {

void project_cluster(const ShapeMatchClusters& clusters, Index k, const SubstepContext& s, Vec3* lambda) {
  thread_local std::vector<Vec3> goals;
  const Index begin = clusters.offsets[k], end = clusters.offsets[k + 1];
  goals.resize(end - begin);
  shape_match_goals(clusters, k, s.x, goals.data());
  const Real omega2 = clusters.omega[k] * clusters.omega[k];
  for (Index e = begin; e < end; ++e) {
    const Index p = clusters.particle[e];
    const Real w = s.inv_mass[p];
    if (w <= 0) continue;
    const Real alpha_tilde = omega2 > 0 ? s.inv_h2 / (clusters.mass[e] * omega2) : 0;
    const Vec3 dl = (-(s.x[p] - goals[e - begin]) - alpha_tilde * lambda[e]) / (w + alpha_tilde);
    lambda[e] += dl;
    s.x[p] += w * dl;
  }
}

}  // namespace

void project_shape_matching(const Model& model, const GrainSleepState& sleep, const SubstepContext& s, Vec3* lambda) {
  const ShapeMatchClusters& clusters = model.shape_matching;
  const Index count = clusters.size();
  auto awake = [&](Index k) { return !sleep.cluster_asleep(clusters.particle[clusters.offsets[k]]); };
  if (clusters.disjoint) {  // each particle in one cluster: the order does not matter
#pragma omp for schedule(static)
    for (Index k = 0; k < count; ++k)
      if (awake(k)) project_cluster(clusters, k, s, lambda);
  } else {
#pragma omp single
    for (Index k = 0; k < count; ++k)
      if (awake(k)) project_cluster(clusters, k, s, lambda);
  }
}

}  // namespace moreau
