#include "moreau/solvers/xpbd/xpbd_solver.hpp"

#include "moreau/solvers/xpbd/xpbd_stages.hpp"
#include "moreau/solvers/xpbd/xpbd_step.hpp"

namespace moreau {

std::vector<std::string> XpbdSolver::stage_names() const { return xpbd_stage_names(); }

void XpbdSolver::step(const Model& model, State& state, StageTimer& timer, int threads) {
  xpbd_step(model, state, workspace_, timer, threads);
}

}  // namespace moreau
