#include "moreau/solvers/xpbd/joint_projection.hpp"

#include <algorithm>

#include "moreau/constraints/joints/joint_frames.hpp"
#include "moreau/solvers/xpbd/project_body_rows.hpp"

namespace moreau {

namespace {

BodyHandle handle_of(const Model& model, State& state, const BodyEnd& e) {
  switch (e.kind) {
    case BodyEndKind::world: return {};
    case BodyEndKind::body: return rigid_body_handle(model.rigid, state.rigid, e.index);
    case BodyEndKind::particle: return particle_handle(state.position[e.index], model.particle_inv_mass[e.index]);
  }
  return {};
}

BodyVelocityHandle velocity_handle_of(const Model& model, State& state, const BodyEnd& e) {
  switch (e.kind) {
    case BodyEndKind::world: return {};
    case BodyEndKind::body: return rigid_body_velocity_handle(model.rigid, state.rigid, e.index);
    case BodyEndKind::particle:
      return particle_velocity_handle(state.velocity[e.index], model.particle_inv_mass[e.index]);
  }
  return {};
}

// Projects each block as the joint hands it on, into the joint's multipliers.
class GaussSeidelProjection final : public BodyRowSink {
 public:
  GaussSeidelProjection(const Model& model, State& state, Real h) : model_(model), state_(state), h_(h) {}
  void set_multipliers(JointMultipliers& lambda) { lambda_ = &lambda; }
  void take(const BodyRows& rows) override {
    const std::array<BodyHandle, 2> ends{handle_of(model_, state_, rows.end[0]), handle_of(model_, state_, rows.end[1])};
    xpbd_project_body_rows(rows, ends, lambda_->data() + rows.slot, h_);
  }

 private:
  const Model& model_;
  State& state_;
  Real h_;
  JointMultipliers* lambda_ = nullptr;
};

}  // namespace

void reset_joints(const Model& model, State& state, Real* drive_start) {
  for (size_t k = 0; k < model.joints.size(); ++k) {
    state.joint_lambda[k].fill(0);
    drive_start[k] = joint_coordinate(model.joints[k], state);
  }
}

void project_joints(const Model& model, State& state, const Real* drive_start, const SubstepStart& start, Real h) {
  GaussSeidelProjection projection(model, state, h);
  for (size_t k = 0; k < model.joints.size(); ++k) {
    const bool direct = model.joint_forest.in_tree(k);  // equality rows already solved (joint_tree.hpp)
    if (direct && !has_other_rows(model.joints[k])) continue;
    projection.set_multipliers(state.joint_lambda[k]);
    joint_rows({state, model.joints[k], h, drive_start[k],
                direct ? JointRowSet::all_but_equality : JointRowSet::all, &start},
               projection);
  }
}

void damp_joints(const Model& model, State& state, Real h) {
  for (const Joint& j : model.joints) {
    if (j.damping <= 0 && j.angular_damping <= 0) continue;
    const BodyVelocityHandle va = velocity_handle_of(model, state, j.ends[0].body());
    const BodyVelocityHandle vb = velocity_handle_of(model, state, j.ends[1].body());
    const JointEndPose a = end_pose(state, j.ends[0]), b = end_pose(state, j.ends[1]);
    const Vec3 ra = a.offset(), rb = b.offset();
    if (j.damping > 0) {
      const Vec3 dv = va.point_velocity(ra) - vb.point_velocity(rb);
      apply_relative_velocity_change(va, vb, -dv * std::min(j.damping * h, Real(1)), ra, rb);
    }
    if (j.angular_damping > 0 && (va.rotates() || vb.rotates())) {
      const Vec3 wa = va.angular_velocity ? *va.angular_velocity : Vec3::Zero();
      const Vec3 wb = vb.angular_velocity ? *vb.angular_velocity : Vec3::Zero();
      const Vec3 dw = -(wa - wb) * std::min(j.angular_damping * h, Real(1));
      const Real len = dw.norm();
      if (len <= 0) continue;
      const Vec3 n = dw / len;
      const Real w = n.dot(va.apply_inv_inertia(n)) + n.dot(vb.apply_inv_inertia(n));
      if (w <= 0) continue;
      const Vec3 p = dw / w;
      if (va.rotates()) *va.angular_velocity += va.apply_inv_inertia(p);
      if (vb.rotates()) *vb.angular_velocity -= vb.apply_inv_inertia(p);
    }
  }
}

}  // namespace moreau
