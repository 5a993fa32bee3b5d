#include "moreau/solvers/nmd/velocity_space.hpp"

#include <algorithm>

#include "moreau/fluids/fluid_heat.hpp"
#include "moreau/model/state.hpp"
#include "moreau/rigid/body_handle.hpp"
#include "moreau/rigid/rigid_motion.hpp"

namespace moreau {

bool VelocitySpace::moves(const VelocityEnd& e) const {
  if (e.size == 0) return false;
  if (e.size == 3) return point_inverse_mass(e.dof) > 0;
  const Index b = (e.dof - 3 * particles) / 6;
  return body_inv_mass[b] > 0 || !body_inv_inertia[b].isZero(0);
}

void VelocitySpace::apply_inverse_mass(const VelocityEnd& e, const Real* jacobian, Real* out) const {
  if (e.size == 3) {
    const Real w = point_inverse_mass(e.dof);
    for (int c = 0; c < 3; ++c) out[c] = w * jacobian[c];
    for (int c = 3; c < 6; ++c) out[c] = 0;
    return;
  }
  const Index b = (e.dof - 3 * particles) / 6;
  const Real w = body_inv_mass[b];
  for (int c = 0; c < 3; ++c) out[c] = w * jacobian[c];
  const Vec3 angular = body_inv_inertia[b] * Vec3(jacobian[3], jacobian[4], jacobian[5]);
  for (int c = 0; c < 3; ++c) out[3 + c] = angular[c];
}

void VelocitySpace::gather(const Model& model, const State& state) {
  particles = model.particle_count();
  bodies = model.rigid.count();
  fluids = state.fluid.count;
  const bool grains = std::any_of(model.particle_inv_inertia.begin(), model.particle_inv_inertia.end(),
                                  [](Real w) { return w > 0; });
  spins = grains ? particles : 0;
  v.resize(3 * (particles + fluids + spins) + 6 * bodies);
  fluid_inv_mass.assign(state.fluid.inv_mass.begin(), state.fluid.inv_mass.begin() + fluids);
  for (Index i = 0; i < fluids; ++i)
    for (int c = 0; c < 3; ++c) v[fluid_dof(i) + c] = state.fluid.velocity[i][c];
  particle_inv_mass.assign(model.particle_inv_mass.begin(), model.particle_inv_mass.end());
  if (state.sleep.asleep_count > 0 || !state.emitters.unborn.empty())  // sleeping and unborn grains keep still
    for (Index p = 0; p < particles; ++p)
      if (state.sleep.asleep(p) || !state.live(p)) particle_inv_mass[p] = 0;
  body_inv_mass.resize(bodies);
  body_inv_inertia.resize(bodies);
  for (Index p = 0; p < particles; ++p)
    for (int c = 0; c < 3; ++c) v[3 * p + c] = state.velocity[p][c];
  spin_inv_inertia.assign(spins, 0);
  for (Index p = 0; p < spins; ++p) {
    if (particle_inv_mass[p] > 0) spin_inv_inertia[p] = model.particle_inv_inertia[p];
    for (int c = 0; c < 3; ++c) v[spin_dof(p) + c] = state.angular_velocity[p][c];
  }
  const RigidBodyModel& m = model.rigid;
  const RigidBodyState& s = state.rigid;
  for (Index b = 0; b < bodies; ++b) {
    const Index d = body_dof(b);
    for (int c = 0; c < 3; ++c) {
      v[d + c] = s.velocity[b][c];
      v[d + 3 + c] = s.angular_velocity[b][c];
    }
    const bool dynamic = m.is_dynamic(b);
    body_inv_mass[b] = dynamic ? m.body_inv_mass[b] : 0;
    body_inv_inertia[b] = dynamic ? world_inverse_inertia(s.orientation[b], m.body_inv_inertia[b]) : Mat3::Zero();
  }
}

void VelocitySpace::apply_forces(const Model& model, const State& state, Real h) {
  const Vec3 dv = h * model.settings.gravity;
  for (Index p = 0; p < particles; ++p) {
    if (particle_inv_mass[p] <= 0) continue;
    for (int c = 0; c < 3; ++c) v[3 * p + c] += dv[c];
  }
  for (Index i = 0; i < fluids; ++i) {
    // A kinematic particle (inverse mass 0: held in an emitter's nozzle) moves on at its velocity.
    if (fluid_inv_mass[i] <= 0) continue;
    // Buoyant fluids weigh by their temperature (fluid_heat.hpp).
    const Vec3 dv_i = model.fluid.buoyant ? Vec3(fluid_weight_factor(model.fluid.phases[state.fluid.phase[i]],
                                                                     state.fluid.enthalpy[i]) * dv)
                                          : dv;
    for (int c = 0; c < 3; ++c) v[fluid_dof(i) + c] += dv_i[c];
  }
  const RigidBodyModel& m = model.rigid;
  for (Index b = 0; b < bodies; ++b) {
    if (!m.is_dynamic(b)) continue;
    const Index d = body_dof(b);
    const Vec3 dw = gyroscopic_velocity_change(state.rigid.orientation[b], Vec3(v[d + 3], v[d + 4], v[d + 5]),
                                               m.body_inertia[b], m.body_inv_inertia[b], h);
    for (int c = 0; c < 3; ++c) {
      v[d + c] += dv[c];
      v[d + 3 + c] += dw[c];
    }
  }
}

void VelocitySpace::scatter(const Model& model, State& state) const {
  for (Index p = 0; p < particles; ++p)
    if (particle_inv_mass[p] > 0) state.velocity[p] = Vec3(v[3 * p], v[3 * p + 1], v[3 * p + 2]);
  for (Index p = 0; p < spins; ++p)
    if (spin_inv_inertia[p] > 0) state.angular_velocity[p] = Vec3(v[spin_dof(p)], v[spin_dof(p) + 1], v[spin_dof(p) + 2]);
  for (Index i = 0; i < fluids; ++i) {
    const Index d = fluid_dof(i);
    state.fluid.velocity[i] = Vec3(v[d], v[d + 1], v[d + 2]);
  }
  for (Index b = 0; b < bodies; ++b) {
    if (!model.rigid.is_dynamic(b)) continue;
    const Index d = body_dof(b);
    state.rigid.velocity[b] = Vec3(v[d], v[d + 1], v[d + 2]);
    state.rigid.angular_velocity[b] = Vec3(v[d + 3], v[d + 4], v[d + 5]);
  }
}

}  // namespace moreau
