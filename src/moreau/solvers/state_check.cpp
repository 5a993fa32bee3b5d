#include "moreau/solvers/state_check.hpp"

#include <fmt/format.h>

#include "moreau/errors.hpp"
#include "moreau/model/state.hpp"

namespace moreau {

namespace {

[[noreturn]] void report_divergence(const State& state, const std::string& object, Index particle, const Vec3& x,
                                    const Vec3& v, Real limit) {
  const bool finite = x.allFinite() && v.allFinite();
  throw NumericalError(fmt::format(
      "simulation diverged at step {} (t = {:.6g} s) in object '{}': particle {} has {} "
      "(limit {} m/s, settings.max_speed); try more substeps, a smaller dt or softer materials",
      state.step, state.time, object, particle,
      finite ? fmt::format("speed {:.3g} m/s", v.norm()) : std::string("a non-finite position or velocity"), limit));
}

}  // namespace

void check_state(const Model& model, const State& state) {
  const Real limit = model.settings.max_speed;
  const FluidState& fluid = state.fluid;
  for (Index i = 0; i < fluid.count; ++i) {
    if (fluid.position[i].allFinite() && fluid.velocity[i].allFinite() && fluid.velocity[i].norm() <= limit) continue;
    const FluidPhase& phase = model.fluid.phases[fluid.phase[i]];
    report_divergence(state, model.objects[phase.object].name, fluid.id[i], fluid.position[i], fluid.velocity[i], limit);
  }
  const RigidBodyState& rb = state.rigid;
  for (Index b = 0; b < model.rigid.count(); ++b) {
    const bool finite = rb.position[b].allFinite() && rb.velocity[b].allFinite() && rb.angular_velocity[b].allFinite() &&
                        rb.orientation[b].coeffs().allFinite();
    if (finite && rb.velocity[b].norm() <= limit) continue;
    const ObjectInfo& obj = model.objects[model.rigid.body_object[b]];
    throw NumericalError(fmt::format(
        "simulation diverged at step {} (t = {:.6g} s) in rigid body '{}': {} (limit {} m/s, settings.max_speed); "
        "try more substeps, a smaller dt or stiffer joints with compliance",
        state.step, state.time, obj.name,
        finite ? fmt::format("speed {:.3g} m/s", rb.velocity[b].norm()) : std::string("a non-finite pose or velocity"),
        limit));
  }
  for (Index p = 0; p < model.particle_count(); ++p) {
    if (!state.live(p)) continue;  // a grain its emitter has not released takes no part
    const bool finite = state.position[p].allFinite() && state.velocity[p].allFinite();
    if (finite && state.velocity[p].norm() <= limit) continue;
    const ObjectInfo& obj = model.objects[model.particle_object[p]];
    report_divergence(state, obj.name, p - obj.particle_begin, state.position[p], state.velocity[p], limit);
  }
  const ContinuumModel& continuum = model.continuum;
  for (Index i = 0; i < state.continuum.size(); ++i) {
    if (state.continuum.deformation[i].allFinite()) continue;
    const Index p = continuum.particle[i];
    const ObjectInfo& obj = model.objects[model.particle_object[p]];
    throw NumericalError(fmt::format(
        "simulation diverged at step {} (t = {:.6g} s) in continuum '{}': particle {} has a non-finite deformation "
        "gradient; try more substeps or a smaller dt",
        state.step, state.time, obj.name, p - obj.particle_begin));
  }
}

}  // namespace moreau
