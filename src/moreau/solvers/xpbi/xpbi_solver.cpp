#include "moreau/solvers/xpbi/xpbi_solver.hpp"

#include "moreau/solvers/xpbd/xpbd_stages.hpp"
#include "moreau/solvers/xpbi/continuum_sweep.hpp"

namespace moreau {

std::array<std::string, 3> ContinuumSubstep::stage_names() const {
  return {"continuum_neighbors", "continuum_constraints", "continuum_update"};
}

void ContinuumSubstep::begin_substep(const Model& model, State& state, int threads) {
  if (model.continuum.empty()) return;
  around_.build(model, state, threads);
  lambda_.assign(model.continuum.size(), 0);
  scratch_.velocity_gradient.resize(model.continuum.size());
  scratch_.smoothed.resize(model.continuum.size());
}

void ContinuumSubstep::project(const Model& model, State& state, const SubstepContext& ctx) {
  if (!model.continuum.empty()) sweep_continuum(model, state, around_, ctx, lambda_);
}

void ContinuumSubstep::end_substep(const Model& model, State& state, const SubstepContext& ctx) {
  if (!model.continuum.empty()) finish_continuum_substep(model, state, around_, ctx, scratch_);
}

std::vector<std::string> XpbiSolver::stage_names() const {
  std::vector<std::string> names = xpbd_stage_names();
  for (const std::string& name : continuum_.stage_names()) names.push_back(name);
  return names;
}

void XpbiSolver::step(const Model& model, State& state, StageTimer& timer, int threads) {
  xpbd_step(model, state, workspace_, timer, threads, &continuum_);
}

}  // namespace moreau
