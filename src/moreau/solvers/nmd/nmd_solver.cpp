#include "moreau/solvers/nmd/nmd_solver.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "moreau/collision/particle_body_contacts.hpp"
#include "moreau/collision/particle_candidates.hpp"
#include "moreau/solvers/nmd/suction_rows.hpp"
#include "moreau/errors.hpp"
#include "moreau/model/state.hpp"
#include "moreau/rigid/rigid_motion.hpp"
#include "moreau/solvers/nmd/nmd_assembly.hpp"
#include "moreau/solvers/nmd/nmd_stages.hpp"
#include "moreau/solvers/nmd/projected_gauss_seidel.hpp"
#include "moreau/solvers/nmd/solve_methods.hpp"
#include "moreau/solvers/state_check.hpp"

namespace moreau {

namespace {

// x+ = x + h v+ for free particles and every moving body; q+ = exp(h w+) q.
void integrate_positions(const Model& model, State& state, Real h) {
  for (Index p = 0; p < model.particle_count(); ++p)
    if (model.particle_inv_mass[p] > 0 && state.live(p)) state.position[p] += h * state.velocity[p];
  RigidBodyState& s = state.rigid;
  for (Index b = 0; b < model.rigid.count(); ++b) {
    if (model.rigid.body_motion[b] == BodyMotion::fixed) continue;
    s.position[b] += h * s.velocity[b];
    s.orientation[b] = rotate_by_angular_velocity(s.orientation[b], s.angular_velocity[b], h);
  }
}

// The contact sets' touching flags from the impulses the solve left (probes and counts read them).
void mark_touching(State& state) {
  RigidContacts& contacts = state.rigid_contacts;
  for (RigidManifold& mf : contacts.manifolds) {
    mf.touching = false;
    mf.sliding = false;
    for (Index i = mf.first; i < mf.first + mf.count; ++i) {
      RigidContactPoint& c = contacts.points[i];
      c.lambda_normal = c.row_impulse[0];
      c.touching = c.lambda_normal != 0;  // pushing, or pulling by adhesion
      mf.touching |= c.touching;
    }
  }
}

}  // namespace

std::vector<std::string> NmdSolver::stage_names() const { return nmd_stage_names(); }

void NmdSolver::solve(const Model& model, const State& state, int threads) {
  const NmdSettings& settings = model.settings.nmd;
  bool solved = true;
  switch (settings.method) {
    case NmdMethod::pgs: projected_gauss_seidel(system_, space_, settings, schedule_, threads); break;
    case NmdMethod::direct:
    case NmdMethod::hybrid: solved = solve_factored(system_, space_, settings, schur_, schedule_, threads); break;
  }
  if (!solved)
    throw NumericalError(fmt::format(
        "the velocity-level system at step {} (t = {:.6g} s) is not positive definite after regularisation; "
        "give the joints or contacts a compliance (settings.nmd.contact_compliance) or use settings.nmd.method \"pgs\"",
        state.step, state.time));
}

void NmdSolver::step(const Model& model, State& state, StageTimer& timer, int threads) {
  threads = std::max(1, threads);
  timer.start();
  if (!model.particle_emitters.empty()) emit_particles(model, state);
  detect_particle_candidates(model, state, contact_scratch_, threads, !model.rigid.empty());
  if (!model.rigid.empty()) detect_rigid_contacts(model, state, threads);
  timer.lap(NmdStage::detect_contacts);

  const NmdSettings& settings = model.settings.nmd;
  const Real h = model.settings.dt / settings.substeps;
  const Real start_time = state.time;
  const bool fluids = !model.fluid.empty();
  if (fluids) fluid_.start_step(model, state, start_time, threads);
  for (int sub = 0; sub < settings.substeps; ++sub) {
    const Real end_time = start_time + (sub + 1) * h;
    if (fluids) {
      fluid_.prepare(model, state, end_time - h, threads);
      timer.lap(NmdStage::fluid_neighbors);
    }
    space_.gather(model, state);
    assemble_nmd_system(model, state, space_, h, end_time, system_, state.nmd_rows, threads);
    if (fluids) fluid_.add_rows(model, state, space_, h, end_time, input_, system_);
    add_suction_rows(model, state, space_, h, end_time - h, input_, system_);
    schedule_.build(system_, static_cast<Index>(space_.v.size()));
    timer.lap(NmdStage::assemble);
    space_.apply_forces(model, state, h);
    warm_start(system_, space_, settings, h);
    solve(model, state, threads);
    store_impulses(system_, h);
    if (fluids) fluid_.store_pressure(model, state, h);
    store_suction(model, state, h);
    timer.lap(NmdStage::solve);
    space_.scatter(model, state);
    integrate_positions(model, state, h);
    if (fluids) fluid_.integrate(model, state, h, end_time);
    mark_touching(state);
    timer.lap(NmdStage::integrate);
  }
  if (fluids) {
    fluid_.finish_step(model, state, model.settings.dt, h, threads);
    timer.lap(NmdStage::fluid_velocity);
  }
  state.time = start_time + model.settings.dt;
  state.step += 1;
  check_state(model, state);
  timer.lap(NmdStage::check_state);
  update_grain_sleep(model, state);
  timer.lap(NmdStage::sleep);
}

}  // namespace moreau
