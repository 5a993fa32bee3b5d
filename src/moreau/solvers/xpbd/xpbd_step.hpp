#pragma once
// One step of the position-level XPBD formulation with substepping.
#include "moreau/model/state.hpp"
#include "moreau/solvers/stage_timer.hpp"

namespace moreau {

/// Advances `state` by model.settings.dt. Throws NumericalError (naming step, time and object)
/// when a position or velocity is not finite or exceeds settings.max_speed.
void xpbd_step(const Model& model, State& state, StageTimer& timer, int threads);
/// The same on solver_thread_count(model) threads.
void xpbd_step(const Model& model, State& state, StageTimer& timer);

/// Number of threads a model's steps use (settings.threads, or all cores when it is 0).
int solver_thread_count(const Model& model);

}  // namespace moreau
