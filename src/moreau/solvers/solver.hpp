#pragma once
// One formulation of the constraint engine behind one interface. A scene's `settings.solver`
// names a registered formulation (solver_registry.hpp); the run loop, the public API, tests and
// benchmarks step it through this interface only. A solver keeps its scratch buffers to itself;
// the Model is read-only and the State holds what a step changes — everything a later step reads,
// warm starts included, since a checkpoint is the State alone. A solver's own buffers must be
// scratch: rewritten before they are read in every step.
#include <string>
#include <string_view>
#include <vector>

#include "moreau/model/state.hpp"
#include "moreau/solvers/stage_timer.hpp"

namespace moreau {

class Solver {
 public:
  virtual ~Solver() = default;
  /// The `settings.solver` value that selects this formulation.
  virtual std::string_view name() const = 0;
  /// Names of the stages step() charges to the timer, indexed by stage number.
  virtual std::vector<std::string> stage_names() const = 0;
  /// Advances `state` by model.settings.dt on `threads` threads (>= 1); the result does not
  /// depend on `threads`. Throws NumericalError naming the step, the time and the object.
  virtual void step(const Model& model, State& state, StageTimer& timer, int threads) = 0;
};

}  // namespace moreau
