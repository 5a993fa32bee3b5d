#pragma once
// The position-level XPBD formulation with substepping (`"solver": "xpbd"`).
#include "moreau/solvers/solver.hpp"
#include "moreau/solvers/xpbd/xpbd_workspace.hpp"

namespace moreau {

class XpbdSolver final : public Solver {
 public:
  std::string_view name() const override { return "xpbd"; }
  std::vector<std::string> stage_names() const override;
  void step(const Model& model, State& state, StageTimer& timer, int threads) override;

 private:
  XpbdWorkspace workspace_;
};

}  // namespace moreau
