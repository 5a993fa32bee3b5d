// Checkpoints of runs solved by PETSc restart bit for bit (checkpoint_restart_check.hpp): a
// transient flow (field split) and a ringing beam (the energy-momentum scheme's nonsymmetric
// tangent, GMRES with GAMG), whose Krylov counters are part of the state.
#include <gtest/gtest.h>

#include "checkpoint_restart_check.hpp"

namespace moreau::test {
namespace {

class PetscCheckpointRestart : public ::testing::TestWithParam<RestartCase> {};

TEST_P(PetscCheckpointRestart, RunOfTwoTEqualsRunOfTThenRestartForT) { expect_seamless_restart(GetParam()); }

INSTANTIATE_TEST_SUITE_P(
    Solvers, PetscCheckpointRestart,
    ::testing::Values(RestartCase{"TransientFlowPetsc", kTransientCavity, {"settings.linear_solver={\"type\": \"petsc\"}"}, 3},
                      RestartCase{"RingingBeamPetsc", "fem_beam.json",
                                  {"settings.linear_solver={\"type\": \"petsc\", \"tolerance\": 1e-10}"}, 4}),
    [](const auto& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace moreau::test
