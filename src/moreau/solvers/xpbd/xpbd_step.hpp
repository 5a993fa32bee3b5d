#pragma once
// One step of the position-level XPBD formulation with substepping.
#include "moreau/model/state.hpp"
#include "moreau/solvers/stage_timer.hpp"
#include "moreau/solvers/xpbd/xpbd_workspace.hpp"

namespace moreau {

/// Advances `state` by model.settings.dt. Throws NumericalError (naming step, time and object)
/// when a position or velocity is not finite or exceeds settings.max_speed.
/// `workspace` holds the solver's buffers between stages (sized here on first use).
void xpbd_step(const Model& model, State& state, XpbdWorkspace& workspace, StageTimer& timer, int threads);

/// Number of threads a model's steps use (settings.threads, or all cores when it is 0).
int solver_thread_count(const Model& model);

}  // namespace moreau
