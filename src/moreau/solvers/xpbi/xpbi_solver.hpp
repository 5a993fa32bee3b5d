#pragma once
// XPBI (`"solver": "xpbi"`): velocity-level XPBD for inelastic continua (Yu, Li, Lan, Yang, Jiang
// 2024, "XPBI: Position-Based Dynamics with Smoothing Kernels Handles Continuum Inelasticity").
//
// Each substep of length h is one step of the paper's Algorithm 1, run inside the XPBD substep
// (xpbd_step.hpp) so that every other row of the engine (contacts, fluids, cloth, soft bodies,
// rigid bodies, joints) acts on the same candidate positions x = x^n + h v in the same iterations:
//   1-2. neighbours of the continuum's particles on x^n, L_p and V^n   (begin_substep: continuum_neighborhood)
//   3.   v += h g, x = x^n + h v, multipliers zeroed                    (XPBD's prediction)
//   4.   every iteration: the continuum's constraints, Gauss-Seidel by block colour, with the
//        return map inside (project: continuum_sweep), then XPBD's rows
//   5-8. v = (x - x^n) / h; XSPH; x = x^n + h v; F^{n+1} = Z((I + h grad v) F^n)
//                                                                        (end_substep: continuum_update)
// followed by XPBD's velocity pass (restitution and friction of the contacts). A correction of
// the positions by dx is the paper's velocity correction dv = dx / h, so the two views are one
// scheme. A scene without continua steps exactly as under `xpbd`.
#include <vector>

#include "moreau/solvers/solver.hpp"
#include "moreau/solvers/xpbd/xpbd_step.hpp"
#include "moreau/solvers/xpbi/continuum_neighborhood.hpp"
#include "moreau/solvers/xpbi/continuum_update.hpp"

namespace moreau {

/// The continuum's part of each substep (the stages above).
class ContinuumSubstep final : public SubstepExtension {
 public:
  std::array<std::string, 3> stage_names() const override;
  void begin_substep(const Model& model, State& state, int threads) override;
  void project(const Model& model, State& state, const SubstepContext& ctx) override;
  void end_substep(const Model& model, State& state, const SubstepContext& ctx) override;

 private:
  ContinuumNeighborhood around_;
  std::vector<Real> lambda_;     // per sweep position (ContinuumNeighborhood), this substep
  ContinuumSubstepScratch scratch_;
};

class XpbiSolver final : public Solver {
 public:
  std::string_view name() const override { return "xpbi"; }
  std::vector<std::string> stage_names() const override;
  void step(const Model& model, State& state, StageTimer& timer, int threads) override;

 private:
  XpbdWorkspace workspace_;
  ContinuumSubstep continuum_;
};

}  // namespace moreau
