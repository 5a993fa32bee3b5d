#include "moreau/model/state.hpp"

namespace moreau {

State make_rest_state(const Model& model) {
  State s;
  const size_t n = model.particle_count();
  s.position = model.particle_rest_position;
  s.velocity.assign(n, Vec3::Zero());
  s.angular_velocity.assign(n, Vec3::Zero());
  s.sleep.resize(s.position);
  for_each_family(model.constraints, s.constraint_lambda, [](const auto& family, auto& lambda, int) {
    lambda.assign(family.size(), zero_multiplier<typename std::decay_t<decltype(family)>::Multiplier>());
  });
  s.fluid = make_fluid_state(model.fluid);
  const RigidBodyModel& rb = model.rigid;
  s.rigid.resize(rb.count());
  s.rigid.position = rb.initial_position;
  s.rigid.orientation = rb.initial_orientation;
  s.rigid.velocity = rb.initial_velocity;
  s.rigid.angular_velocity = rb.initial_angular_velocity;
  s.joint_lambda.assign(model.joints.size(), JointMultipliers{});
  s.suction.assign(model.suction_cups.size(), SuctionCupState{});
  prepare_particle_emitters(model, s);
  s.continuum = make_continuum_state(model.continuum);
  return s;
}

}  // namespace moreau
