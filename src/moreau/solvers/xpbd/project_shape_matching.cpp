#include "moreau/solvers/xpbd/project_shape_matching.hpp"

#include <vector>

#include "moreau/model/model.hpp"

namespace moreau {

void project_shape_matching(const Model& model, const SubstepContext& s) {
  const ShapeMatchClusters& clusters = model.shape_matching;
  thread_local std::vector<Vec3> goals;
  for (Index k = 0; k < clusters.size(); ++k) {
    const Index begin = clusters.offsets[k], end = clusters.offsets[k + 1];
    goals.resize(end - begin);
    shape_match_goals(clusters, k, s.x, goals.data());
    const Real share = shape_match_share(clusters.omega[k], s.h);
    for (Index e = begin; e < end; ++e) {
      const Index p = clusters.particle[e];
      if (s.inv_mass[p] > 0) s.x[p] += share * (goals[e - begin] - s.x[p]);
    }
  }
}

}  // namespace moreau
