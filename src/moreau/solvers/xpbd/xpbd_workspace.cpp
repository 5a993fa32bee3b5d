#include "moreau/solvers/xpbd/xpbd_workspace.hpp"

#include "moreau/model/model.hpp"

namespace moreau {

void XpbdWorkspace::fit(const Model& model) {
  const size_t n = model.particle_count();
  if (substep_start.size() != n) substep_start.assign(n, Vec3::Zero());
  if (velocity_before.size() != n) velocity_before.assign(n, Vec3::Zero());
  if (substep_turn.size() != n) substep_turn.assign(n, Vec3::Zero());
  shape_match_lambda.resize(model.shape_matching.particle.size(), Vec3::Zero());
  bodies.fit(model.rigid.count());
  fluid.fit(model.fluid);
  if (joint_drive_start.size() != model.joints.size()) joint_drive_start.assign(model.joints.size(), 0);
}

}  // namespace moreau
