// "linear_solver": {"type": "petsc"} in scene files, through the `moreau` program: a flow and a
// solid run with it to the direct solvers' answers, and what it refuses (exit 2, naming the key).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "scene_test_helpers.hpp"
#include "test_helpers.hpp"

namespace moreau {
namespace {

namespace fs = std::filesystem;

// The 3D lid-driven cube of scenes/cavity3d_re400.json at Re 100 on 8^3 cells.
std::string cavity(const std::string& linear_solver) {
  return std::string(R"({"name": "cavity", "settings": {"solver": "fem", "integrator": "steady", "gravity": [0, 0, 0],
      "newton": {"tolerance": 1e-11}, "linear_solver": )") + linear_solver + R"(},
    "objects": [{"name": "fluid", "kind": "fluid", "mesh": {"type": "box", "min": [0, 0, 0], "max": [1, 1, 1], "cells": [8, 8, 8]},
      "density": 1.0, "viscosity": 0.01,
      "boundaries": [{"where": {"side": "top"}, "velocity": ["1", "0", "0"]},
                     {"where": {"side": ["left", "right", "bottom", "back", "front"]}, "type": "no_slip"}],
      "pressure_reference": {"mean": 0}}],
    "probes": [{"name": "centre", "type": "point", "at": [0.5, 0.5, 0.5]}]})";
}

using test::expect_bad_scene;

TEST(PetscScenes, AFlowSceneGivesTheDirectSolversProbes) {
  // Newton to 1e-11 either way, Krylov solves to 1e-10: the solutions then differ by about
  // cond(J) 1e-11 |x| (as in test_petsc_flow.cpp, where the states agree to 1e-15 or better), so
  // the probes (velocity ~0.1 m/s, pressure ~0.01 Pa) agree to 1e-9; probes.csv keeps 17 digits.
  const auto direct = test::run_scene(test::write_scene("petsc_direct", cavity(R"({"type": "direct"})")), test::temp_dir("petsc_direct_run") + "/out");
  const std::string out = test::temp_dir("petsc_fieldsplit") + "/out";
  const auto petsc = test::run_scene(test::write_scene("petsc_fieldsplit_scene", cavity(R"({"type": "petsc", "tolerance": 1e-10})")), out);
  ASSERT_FALSE(direct.empty());
  ASSERT_EQ(direct.size(), petsc.size());
  for (size_t c = 1; c < direct.back().size(); ++c) EXPECT_NEAR(direct.back()[c], petsc.back()[c], 1e-9) << "column " << c;
  std::ifstream run_file(out + "/run.json");
  const nlohmann::json run = nlohmann::json::parse(run_file);
  EXPECT_EQ(run["linear_solver"]["type"], "petsc fgmres+fieldsplit");
  EXPECT_EQ(run["linear_solver"]["solves"], run["newton"]["iterations"]);
  EXPECT_GT(run["linear_solver"]["krylov_iterations"].get<long>(), 0);
}

TEST(PetscScenes, BadPetscSettingsAreRefusedBeforeTheRun) {
  expect_bad_scene("petsc_pc", cavity(R"({"type": "petsc", "preconditioner": "jacobi"})"),
             {"settings.linear_solver.preconditioner", "fieldsplit, fieldsplit_ilu, amg, ilu, lu"});
  expect_bad_scene("petsc_options", cavity(R"({"type": "petsc", "petsc_options": "-pc_type nonsense"})"),
             {"settings.linear_solver.petsc_options", "PETSc does not accept", "nonsense"});
  // Inner solvers read their options only when the preconditioner is built (the field split's
  // blocks) or first applied (block Jacobi's sub-solvers): the check builds one and solves once.
  expect_bad_scene("petsc_inner_options", cavity(R"({"type": "petsc", "petsc_options": "-fieldsplit_u_pc_type nonsense"})"),
             {"settings.linear_solver.petsc_options", "PETSc does not accept", "nonsense"});
  expect_bad_scene("petsc_block_options",
                   cavity(R"({"type": "petsc", "preconditioner": "fieldsplit_ilu", "petsc_options": "-fieldsplit_u_sub_pc_type nonsense"})"),
                   {"settings.linear_solver.petsc_options", "PETSc does not accept", "nonsense"});
  expect_bad_scene("petsc_gmres_key", cavity(R"({"type": "petsc", "drop_tolerance": 1e-3})"),
             {"settings.linear_solver.drop_tolerance", "\"type\": \"gmres\""});
  expect_bad_scene("petsc_key_on_direct", cavity(R"({"type": "direct", "preconditioner": "amg"})"),
             {"settings.linear_solver.preconditioner", "\"type\": \"petsc\""});
}

// A misspelt option is not an error to PETSc (it is never read): the run goes on and warns, naming
// it. The presets' own options are all read, and those a user's option leaves unread (BoomerAMG's,
// when the velocity block is given LU) are not the user's to fix: neither warns.
TEST(PetscScenes, OptionsPetscDoesNotReadAreNamedInAWarning) {
  const std::string out = test::temp_dir("petsc_unused") + "/out";
  const auto typo = test::run_moreau(fmt::format(
      "run {} --out {} --quiet",
      test::write_scene("petsc_unused", cavity(R"({"type": "petsc", "petsc_options": "-fieldsplit_u_pc_typ jacobi"})")), out));
  EXPECT_EQ(typo.exit_code, 0) << typo.output;
  EXPECT_NE(typo.output.find("warning: settings.linear_solver.petsc_options: PETSc did not read -fieldsplit_u_pc_typ"),
            std::string::npos)
      << typo.output;
  for (const std::string settings : {R"("preconditioner": "fieldsplit")", R"("preconditioner": "fieldsplit_ilu")",
                                     R"("preconditioner": "amg")", R"("preconditioner": "ilu")", R"("preconditioner": "lu")",
                                     R"("petsc_options": "-fieldsplit_u_pc_type lu")"}) {
    const auto clean = test::run_moreau(fmt::format(
        "run {} --out {} --quiet",
        test::write_scene("petsc_preset", cavity(fmt::format(R"({{"type": "petsc", {}}})", settings))),
        test::temp_dir("petsc_preset") + "/out"));
    EXPECT_EQ(clean.exit_code, 0) << clean.output;
    EXPECT_EQ(clean.output.find("warning"), std::string::npos) << settings << ": " << clean.output;
  }
  // A static solid's CG falls back to GMRES around the same multigrid: an option of that solver
  // alone is read by it, and so not named.
  const auto solid = test::run_moreau(fmt::format(
      "run {} --out {} --quiet",
      test::write_scene("petsc_solid_options", R"({"name": "block", "settings": {"solver": "fem", "integrator": "static",
          "dt": 1, "duration": 1, "gravity": [0, 0, 0],
          "linear_solver": {"type": "petsc", "petsc_options": "-ksp_gmres_restart 80 -pc_gamg_threshol 0.01"}},
        "objects": [{"name": "b", "kind": "solid", "mesh": {"type": "box", "min": [0, 0, 0], "max": [1, 1, 1], "cells": [3, 3, 3], "element": "hex8"},
          "material": {"model": "neo_hookean", "youngs_modulus": 1e6, "poisson_ratio": 0.3, "density": 1000},
          "loads": [{"type": "traction", "where": {"boundary": "top"}, "value": [0, -1e3, 0]}],
          "dirichlet": [{"where": {"boundary": "bottom"}, "value": [0, 0, 0]}]}]})"),
      test::temp_dir("petsc_solid_options") + "/out"));
  EXPECT_EQ(solid.exit_code, 0) << solid.output;
  EXPECT_NE(solid.output.find("PETSc did not read -pc_gamg_threshol when"), std::string::npos) << solid.output;
  EXPECT_EQ(solid.output.find("-ksp_gmres_restart"), std::string::npos) << solid.output;
}

TEST(PetscScenes, AMissingPluginIsBadInputThatSaysWhereItWasLookedFor) {
  const std::string path = test::write_scene("petsc_missing", cavity(R"({"type": "petsc"})"));
  const std::string out = fs::path(path).parent_path() / "out";
  setenv("MOREAU_PETSC_PLUGIN", "/nowhere/libmoreau_petsc.so", 1);
  const auto r = test::run_moreau(fmt::format("run {} --out {} --quiet", path, out));
  unsetenv("MOREAU_PETSC_PLUGIN");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("settings.linear_solver.type"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("/nowhere/libmoreau_petsc.so: not there"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace
}  // namespace moreau
