#include "moreau/solvers/xpbd/xpbd_step.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>

#include "moreau/solvers/xpbd/project_fluid_density.hpp"
#include "moreau/fluids/ambient_air.hpp"
#include "moreau/fluids/fluid_emitter.hpp"
#include "moreau/fluids/fluid_heat.hpp"
#include "moreau/fluids/fluid_motion.hpp"
#include "moreau/fluids/fluid_neighbors.hpp"
#include "moreau/fluids/fluid_velocity.hpp"
#include "moreau/fluids/fluid_viscosity.hpp"
#include "moreau/fluids/interfacial_tension.hpp"
#include "moreau/fluids/phase_drift.hpp"
#include "moreau/fluids/solid_coupling.hpp"
#include "moreau/fluids/surface_tension.hpp"
#include "moreau/fluids/wall_adhesion.hpp"
#include "moreau/model/particle_emitter.hpp"
#include "moreau/collision/particle_body_contacts.hpp"
#include "moreau/collision/particle_candidates.hpp"
#include "moreau/rigid/rigid_motion.hpp"
#include "moreau/rigid/tree_contacts.hpp"
#include "moreau/solvers/xpbd/joint_projection.hpp"
#include "moreau/solvers/xpbd/particle_body_contact_projection.hpp"
#include "moreau/solvers/xpbd/particle_contact_projection.hpp"
#include "moreau/solvers/xpbd/project_shape_matching.hpp"
#include "moreau/solvers/xpbd/rigid_contact_projection.hpp"
#include "moreau/solvers/xpbd/particle_projections.hpp"
#include "moreau/solvers/state_check.hpp"
#include "moreau/solvers/xpbd/xpbd_stages.hpp"

namespace moreau {

int solver_thread_count(const Model& model) {
  return model.settings.threads > 0 ? model.settings.threads : omp_get_max_threads();
}

namespace {

// Visits, on this thread's share, the particles a substep moves: every live particle, or with
// settings.sleep those not asleep (a sleeping grain keeps its place and zero velocity, and takes
// part in no contact; its substep start is set again in the first substep after it wakes). A
// grain its emitter has not released is not live (model/particle_emitter.hpp).
template <class F>
void for_each_moving_particle(const Model& model, const State& state, F&& f) {
  if (model.settings.sleep.enabled) {
    const std::vector<Index>& awake = state.sleep.awake;
    const Index m = static_cast<Index>(awake.size());
#pragma omp for schedule(static) nowait
    for (Index k = 0; k < m; ++k)
      if (state.live(awake[k])) f(awake[k]);
  } else {
    const Index n = model.particle_count();
#pragma omp for schedule(static) nowait
    for (Index p = 0; p < n; ++p)
      if (state.live(p)) f(p);
  }
}

// x_start = x; v += h g; x += h v (Mueller 2020, Algorithm 2) for free particles; a grain's
// rotation over the substep starts at h omega (no torque acts on a sphere between contacts).
// Also clears the multipliers.
void predict(const Model& model, State& state, XpbdWorkspace& work, Real h) {
  const Vec3 dv = h * model.settings.gravity;
  for_each_moving_particle(model, state, [&](Index p) {
    work.substep_start[p] = state.position[p];
    if (model.particle_inv_inertia[p] > 0) work.substep_turn[p] = h * state.angular_velocity[p];
    if (state.held(p)) {  // in its emitter's nozzle: on at the emitter's velocity, gravity carried by the pipe
      work.velocity_before[p] = state.velocity[p];
      state.position[p] += h * state.velocity[p];
      return;
    }
    if (model.particle_inv_mass[p] <= 0) return;
    state.velocity[p] += dv;
    work.velocity_before[p] = state.velocity[p];
    state.position[p] += h * state.velocity[p];
  });
  auto clear = [](auto& values, auto zero) {
    const Index m = static_cast<Index>(values.size());
#pragma omp for schedule(static) nowait
    for (Index k = 0; k < m; ++k) values[k] = zero;
  };
  for_each_family(model.constraints, state.constraint_lambda, [&](const auto& family, auto& lambda, int) {
    clear(lambda, zero_multiplier<typename std::decay_t<decltype(family)>::Multiplier>());
  });
  clear(state.collider_contacts.lambda_normal, Real{0});
  clear(state.particle_contacts.lambda_normal, Real{0});
  clear(state.collider_contacts.lambda_friction, Vec3::Zero());
  clear(state.collider_contacts.lambda_rolling, Vec3::Zero());
  clear(state.particle_contacts.lambda_friction, Vec3::Zero());
  clear(state.particle_contacts.lambda_rolling, Vec3::Zero());
  clear(work.shape_match_lambda, Vec3::Zero());
#pragma omp barrier
}

// v = (x - x_start) / h; a grain's omega = theta / h, theta its rotation over the substep.
void update_velocity(const Model& model, State& state, const XpbdWorkspace& work, Real h) {
  for_each_moving_particle(model, state, [&](Index p) {
    if (model.particle_inv_mass[p] <= 0 || state.held(p)) return;
    state.velocity[p] = (state.position[p] - work.substep_start[p]) / h;
    if (model.particle_inv_inertia[p] > 0) state.angular_velocity[p] = work.substep_turn[p] / h;
  });
#pragma omp barrier
}

}  // namespace

void xpbd_step(const Model& model, State& state, XpbdWorkspace& work, StageTimer& timer, int threads,
               SubstepExtension* extension) {
  threads = std::max(1, threads);
  timer.start();
  work.fit(model);
  if (!model.particle_emitters.empty()) emit_particles(model, state);
  const Real* inv_mass = model.particle_inv_mass.data();
  if (state.emitters.holds_layers()) {  // particles in a nozzle do not yield to the projections
    work.moving_inv_mass.resize(model.particle_count());
    for (Index p = 0; p < model.particle_count(); ++p) work.moving_inv_mass[p] = moving_inverse_mass(model, state, p);
    inv_mass = work.moving_inv_mass.data();
  }
  // Rigid bodies, or joints alone (a joint may hold a particle to the world).
  const bool rigid = !model.rigid.empty() || !model.joints.empty();
  detect_particle_candidates(model, state, work.contact_scratch, threads, rigid);
  if (rigid) detect_rigid_contacts(model, state, threads);
  timer.lap(XpbdStage::detect_contacts);

  const Real dt = model.settings.dt;
  const int substeps = model.settings.substeps, iterations = model.settings.iterations;
  const Real h = dt / substeps;
  const SubstepContext ctx{.x = state.position.data(),
                           .x_start = work.substep_start.data(),
                           .inv_mass = inv_mass,
                           .h = h,
                           .turn = work.substep_turn.data(),
                           .inv_inertia = model.particle_inv_inertia.data()};
  const SubstepStart start = work.substep_start_view();
  const Real start_time = state.time;
  const bool fluids = !model.fluid.empty(), coupled_solids = model.fluid.solid.size() > 0;
  const bool implicit_viscosity =
      fluids && model.fluid.viscosity_solver == ViscositySolver::implicit_solve && fluid_has_viscosity(model);
  FluidState& fluid = state.fluid;
  if (model.fluid.phase_drift) drift_phases(model, fluid, work.fluid, state.step, threads);  // before new particles
  if (!model.fluid.emitters.empty()) emit_fluid(model, fluid, start_time);

  constexpr int extension_stage = xpbd_family_stage(kParticleFamilyCount);  // the extension's stages follow XPBD's
  auto lap = [&](auto stage) {
#pragma omp master
    timer.lap(stage);
  };
  // One substep, on every thread of a parallel region.
  auto substep = [&](int sub) {
    const Real substep_end = start_time + (sub + 1) * h;
    if (rigid) {
#pragma omp single
      {
        reset_joints(model, state, work.joint_drive_start.data());
        reset_rigid_contacts(state);
        reset_particle_body_contacts(state);
        choose_tree_contacts(model, state);
      }
    }
    predict(model, state, work, h);
    if (rigid) predict_rigid_bodies(model, state.rigid, work.bodies, h);
    if (fluids) predict_fluid(model, fluid, work.fluid, h);
    lap(XpbdStage::predict);
    if (fluids) {
      if (model.fluid.boundary.moving) place_boundary_samples(model, fluid, substep_end);
      if (coupled_solids) place_solid_samples(model, state);
      // The kernel cache's rows follow the lists: laid out when they are rebuilt, and at each step's
      // start (the solver's buffers are scratch; a restored State may hold other lists).
      if (update_fluid_neighbors(model, fluid, work.fluid, substep_end) || sub == 0) lay_out_pair_cache(fluid, work.fluid);
      if (coupled_solids) split_solid_masses(model, fluid, work.fluid);
      lap(XpbdStage::fluid_neighbors);
    }
    for (int it = 0; it < iterations; ++it) {
      if (extension) {
        extension->project(model, state, ctx);
        lap(extension_stage + 1);
      }
      for_each_family(model.constraints, state.constraint_lambda, [&](const auto& family, auto& lambda, int index) {
        xpbd_project(family, lambda.data(), ctx);
        lap(xpbd_family_stage(index));
      });
      if (!model.shape_matching.empty()) {
        project_shape_matching(model, state.sleep, ctx, work.shape_match_lambda.data());
        lap(XpbdStage::shape_matching);
      }
      // The fluid before the contacts: what it pushes into a collider, the contacts push out.
      if (fluids) {
        if (coupled_solids) place_solid_samples(model, state);
        project_fluid_density(model, fluid, work.fluid, h);
        if (coupled_solids) apply_solid_reactions(model, state, work.fluid);
        apply_fluid_corrections(model, fluid, work.fluid, h, substep_end);
        if (coupled_solids) {
          place_solid_samples(model, state);
          project_solid_contacts(model, state, work.fluid, substep_end);
        }
        lap(XpbdStage::fluid_density);
      }
      project_particle_contacts(model, state, ctx);
      lap(XpbdStage::particle_contacts);
      project_collider_contacts(model, state, ctx, substep_end);
      lap(XpbdStage::collider_contacts);
      if (rigid) {
#pragma omp single
        {
          solve_joint_forest(model, state, start, h);
          project_joints(model, state, work.joint_drive_start.data(), start, h);
          timer.lap(XpbdStage::joints);
          project_rigid_contacts(model, state, start);
          project_particle_body_contacts(model, state, start, h);
          timer.lap(XpbdStage::rigid_contacts);
        }
      }
    }
    update_velocity(model, state, work, h);
    if (rigid) update_rigid_body_velocities(model, state.rigid, work.bodies, h);
    if (fluids) update_fluid_velocity(fluid, work.fluid, h);
    lap(XpbdStage::update_velocity);
    if (fluids && implicit_viscosity) {
      apply_implicit_fluid_viscosity(model, state, work.fluid, h);
      lap(XpbdStage::fluid_velocity);
    }
    if (extension) {
      extension->end_substep(model, state, ctx);
      lap(extension_stage + 2);
    }
    particle_contact_velocities(model, state, work.velocity_before.data(), h);
    collider_contact_velocities(model, state, work.velocity_before.data(), h);
    if (rigid) {
#pragma omp single
      {
        accumulate_stuck_slip(state, start);
        rigid_contact_velocities(model, state, work.bodies, h);
        particle_body_contact_velocities(model, state, work.velocity_before.data(), work.bodies, h);
        damp_joints(model, state, h);
      }
    }
#pragma omp barrier
    lap(XpbdStage::velocity_pass);
  };
  auto finish_fluids = [&] {
    apply_fluid_velocity_corrections(model, fluid, work.fluid, dt);
    apply_ambient_air(model, fluid, dt);
    apply_fluid_surface_tension(model, fluid, work.fluid, dt);
    apply_fluid_wall_adhesion(model, fluid, dt, start_time + dt);
    apply_fluid_interfacial_tension(model, fluid, work.fluid, dt);
    lap(XpbdStage::fluid_velocity);
    if (model.fluid.thermal) {
      apply_fluid_heat(model, fluid, work.fluid, dt);
      lap(XpbdStage::fluid_heat);
    }
  };
  if (!extension) {  // one parallel region for the whole step
#pragma omp parallel num_threads(threads)
    {
      for (int sub = 0; sub < substeps; ++sub) substep(sub);
      if (fluids) finish_fluids();
    }
  } else {  // the extension works between substeps, outside the parallel region
    for (int sub = 0; sub < substeps; ++sub) {
      extension->begin_substep(model, state, threads);
      timer.lap(extension_stage);
#pragma omp parallel num_threads(threads)
      substep(sub);
    }
    if (fluids) {
#pragma omp parallel num_threads(threads)
      finish_fluids();
    }
  }
  if (fluids) fluid_cfl_number(model, fluid, h);

  state.time = start_time + dt;
  state.step += 1;
  check_state(model, state);
  timer.lap(XpbdStage::check_state);
  update_grain_sleep(model, state);
  timer.lap(XpbdStage::sleep);
}

}  // namespace moreau
