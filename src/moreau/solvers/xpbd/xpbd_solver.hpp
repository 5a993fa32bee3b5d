#pragma once
// The position-level XPBD formulation with substepping (`"solver": "xpbd"`).
#include "moreau/solvers/solver.hpp"

namespace moreau {

class XpbdSolver final : public Solver {
 public:
  std::string_view name() const override { return "xpbd"; }
  std::vector<std::string> stage_names() const override;
  void step(const Model& model, State& state, StageTimer& timer, int threads) override;
};

}  // namespace moreau
