#pragma once
// The velocity-level nonsmooth multidomain dynamics formulation (`"solver": "nmd"`): per step,
// v+ from the regularised, stabilised MLCP over every row of the constraint engine
// (nmd_system.hpp), then x+ = x + h v+ (symplectic Euler; orientations turned exactly by w+ h).
#include <string>

#include "moreau/collision/particle_contacts.hpp"
#include "moreau/solvers/nmd/constraint_fluid.hpp"
#include "moreau/solvers/nmd/nmd_assembly.hpp"
#include "moreau/solvers/nmd/nmd_system.hpp"
#include "moreau/solvers/nmd/schur_complement.hpp"
#include "moreau/solvers/nmd/sweep_schedule.hpp"
#include "moreau/solvers/solver.hpp"

namespace moreau {

class NmdSolver final : public Solver {
 public:
  std::string_view name() const override { return "nmd"; }
  std::vector<std::string> stage_names() const override;
  void step(const Model& model, State& state, StageTimer& timer, int threads) override;

 private:
  void solve(const Model& model, const State& state, int threads);

  VelocitySpace space_;
  NmdSystem system_;
  SchurComplement schur_;
  SweepSchedule schedule_;  // the sweeps' order for threads (rebuilt after each assembly)
  ContactScratch contact_scratch_;
  ConstraintFluid fluid_;
  NmdBlockInput input_;  // the fluid rows' block being built (its buffers kept from step to step)
};

}  // namespace moreau
