#pragma once
// One step of the position-level XPBD formulation with substepping.
#include <array>
#include <string>

#include "moreau/model/state.hpp"
#include "moreau/solvers/stage_timer.hpp"
#include "moreau/solvers/xpbd/substep_context.hpp"
#include "moreau/solvers/xpbd/xpbd_workspace.hpp"

namespace moreau {

/// What a formulation built on the XPBD substep adds to it (XPBI's continua, solvers/xpbi/). Its
/// three stages are timed after XPBD's (xpbd_stage_names(), then stage_names()).
class SubstepExtension {
 public:
  virtual ~SubstepExtension() = default;
  /// The names of the three stages below, in order.
  virtual std::array<std::string, 3> stage_names() const = 0;
  /// Before each substep, outside any parallel region (it may open its own on `threads` threads);
  /// state.position holds the substep's start.
  virtual void begin_substep(const Model& model, State& state, int threads) = 0;
  /// In every iteration, before the other constraints, on every thread of the substep's region.
  virtual void project(const Model& model, State& state, const SubstepContext& ctx) = 0;
  /// After the velocity update v = (x - x_start) / h and before the contacts' velocity pass, on
  /// every thread of the substep's region.
  virtual void end_substep(const Model& model, State& state, const SubstepContext& ctx) = 0;
};

/// Advances `state` by model.settings.dt. Throws NumericalError (naming step, time and object)
/// when a position or velocity is not finite or exceeds settings.max_speed.
/// `workspace` holds the solver's buffers between stages (sized here on first use).
void xpbd_step(const Model& model, State& state, XpbdWorkspace& workspace, StageTimer& timer, int threads,
               SubstepExtension* extension = nullptr);

/// Number of threads a model's steps use (settings.threads, or all cores when it is 0).
int solver_thread_count(const Model& model);

}  // namespace moreau
