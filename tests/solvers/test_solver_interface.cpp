// The solver seam: scenes select a registered formulation by settings.solver, and stepping through
// the Solver interface is the formulation's own step, bit for bit, for any thread count.
#include <gtest/gtest.h>

#include "moreau/solvers/solver_registry.hpp"
#include "moreau/solvers/xpbd/xpbd_stages.hpp"
#include "test_helpers.hpp"

using namespace moreau;

namespace {
const std::string kShowcase = std::string(MOREAU_SOURCE_DIR) + "/scenes/showcase.json";
}

TEST(SolverRegistry, MakesExactlyTheRegisteredFormulations) {
  EXPECT_EQ(registered_solver_names(), (std::vector<std::string>{"xpbd", "nmd", "xpbi"}));
  const Model model;
  for (const std::string name : {"xpbd", "nmd", "xpbi"}) {
    const auto solver = make_solver(name, model);
    ASSERT_TRUE(solver) << name;
    EXPECT_EQ(solver->name(), name);
    EXPECT_EQ(solver_refusal(name, model), "") << name;
  }
  // The scene format names the FEM engine too, but it is not a formulation of the constraint engine.
  EXPECT_FALSE(make_solver("fem", model));
}

// XPBI adds the continua to the XPBD substep; a scene without continua steps exactly as under xpbd.
TEST(SolverInterface, XpbiStepsASceneWithoutContinuaExactlyAsXpbd) {
  Scene xpbi = load_scene(kShowcase, {"settings.solver=\"xpbi\""}), xpbd = load_scene(kShowcase);
  StageTimer timer;
  for (int s = 0; s < 20; ++s) {
    xpbi.formulation->step(xpbi.model, xpbi.state, timer, 2);
    xpbd.formulation->step(xpbd.model, xpbd.state, timer, 1);
  }
  EXPECT_TRUE(xpbi.state.position == xpbd.state.position);
  EXPECT_TRUE(xpbi.state.velocity == xpbd.state.velocity);
}

// The showcase (cloth with isometric bending, Neo-Hookean tets, a sphere and a floor) for 20 steps:
// through the interface on two threads and through xpbd_step on one, the same bits; and every
// stage the step timed has a name, with time charged to each family the scene has.
TEST(SolverInterface, StepsExactlyAsTheFormulationAndNamesEveryStageItTimes) {
  Scene through_interface = load_scene(kShowcase), direct = load_scene(kShowcase);
  ASSERT_TRUE(through_interface.formulation);
  StageTimer timer, direct_timer;
  XpbdWorkspace direct_workspace;
  for (int s = 0; s < 20; ++s) {
    through_interface.formulation->step(through_interface.model, through_interface.state, timer, 2);
    xpbd_step(direct.model, direct.state, direct_workspace, direct_timer, 1);
  }
  ASSERT_EQ(through_interface.state.position.size(), direct.state.position.size());
  for (size_t p = 0; p < direct.state.position.size(); ++p) {
    ASSERT_EQ(through_interface.state.position[p], direct.state.position[p]) << "particle " << p;
    ASSERT_EQ(through_interface.state.velocity[p], direct.state.velocity[p]) << "particle " << p;
  }
  EXPECT_EQ(through_interface.state.time, direct.state.time);

  const std::vector<std::string> names = through_interface.formulation->stage_names();
  for (int stage = static_cast<int>(names.size()); stage < static_cast<int>(names.size()) + 8; ++stage)
    EXPECT_EQ(timer.seconds(stage), 0.0) << "time charged to unnamed stage " << stage;
  const Model& m = through_interface.model;
  for_each_family(m.constraints, [&](const auto& family, int index) {
    if (family.size() == 0) return;
    EXPECT_EQ(names[xpbd_family_stage(index)], family.kName);
    EXPECT_GT(timer.seconds(xpbd_family_stage(index)), 0.0) << family.kName;
  });
}
