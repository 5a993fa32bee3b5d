// Distributed runs, `mpirun -np 2 moreau run scene.json`, against the same scene on one process:
// a steady flow (the 2D lid-driven cavity), a transient flow (the cavity started from rest by
// BDF2) and a solid (a hex block under load). Every rank holds the whole state and solves its
// rows of each system with PETSc; rank 0 writes the output. Two ranks' preconditioners differ
// from one's (hypre's and GAMG's coarsening are per rank), so the solutions agree to the solver
// tolerances, not bit for bit.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "checkpoint_restart_check.hpp"
#include "scene_test_helpers.hpp"
#include "test_helpers.hpp"

namespace moreau {
namespace {

namespace fs = std::filesystem;

#ifndef MOREAU_MPIEXEC
#define MOREAU_MPIEXEC ""
#endif

// mpirun with `ranks` processes of the moreau program. --oversubscribe: more ranks than free cores
// (CI has two, and ctest runs two tests at once); --bind-to none for the same reason. Open MPI
// refuses to run as root unless told twice (CI's containers run as root). A run that hangs (ranks
// waiting for each other) is ended after 5 minutes, and fails its test by the exit code (124).
test::CommandResult run_on_ranks(int ranks, const std::string& args) {
  const std::string log = test::temp_dir("mpi_cli") + "/log.txt";
  const std::string command = fmt::format(
      "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 timeout 300 {} -np {} --oversubscribe --bind-to none {} {} > {} 2>&1",
      MOREAU_MPIEXEC, ranks, MOREAU_BINARY, args, log);
  const int status = std::system(command.c_str());
  std::ifstream in(log);
  return {WEXITSTATUS(status), std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>())};
}

class MpiRuns : public ::testing::Test {
 protected:
  void SetUp() override {
    if (std::string(MOREAU_MPIEXEC).empty() || !fs::exists(MOREAU_MPIEXEC))
      GTEST_SKIP() << "no mpirun was found when the tests were configured (scripts/install-deps.sh installs Open MPI)";
  }

  // The scene on one process (plain `moreau run`) and on two ranks; returns both output directories.
  std::pair<std::string, std::string> run_both(const std::string& tag, const std::string& scene) {
    const std::string path = test::write_scene(tag, scene);
    const std::string one = fs::path(path).parent_path() / "one", two = fs::path(path).parent_path() / "two";
    const auto serial = test::run_moreau(fmt::format("run {} --out {} --quiet", path, one));
    EXPECT_EQ(serial.exit_code, 0) << serial.output;
    const auto distributed = run_on_ranks(2, fmt::format("run {} --out {} --quiet", path, two));
    EXPECT_EQ(distributed.exit_code, 0) << distributed.output;
    return {one, two};
  }
};

// Every number of two CSV files of the same shape agrees to `tolerance` times the largest
// magnitude in its probe's columns (those whose names share the part before the last '.', such as
// tip.x, tip.y, tip.z: a component that stays at round-off beside the others is measured by them).
void expect_same_csv(const std::string& a_file, const std::string& b_file, double tolerance) {
  const auto read = [](const std::string& file, std::vector<std::string>& names) {
    std::ifstream in(file);
    std::string line, cell;
    std::getline(in, line);
    std::stringstream header(line);
    while (std::getline(header, cell, ',')) names.push_back(cell.substr(0, cell.rfind('.')));
    std::vector<std::vector<double>> rows;
    while (std::getline(in, line)) {
      std::vector<double>& row = rows.emplace_back();
      std::stringstream cells(line);
      while (std::getline(cells, cell, ',')) row.push_back(std::stod(cell));
    }
    return rows;
  };
  std::vector<std::string> names, b_names;
  const auto a = read(a_file, names), b = read(b_file, b_names);
  ASSERT_FALSE(a.empty()) << a_file;
  ASSERT_EQ(a.size(), b.size()) << b_file;
  ASSERT_EQ(names, b_names) << b_file;
  for (size_t c = 0; c < a[0].size(); ++c) {
    double scale = 0;
    for (const auto& row : a)
      for (size_t k = 0; k < row.size(); ++k)
        if (names[k] == names[c]) scale = std::max(scale, std::abs(row[k]));
    for (size_t r = 0; r < a.size(); ++r) {
      ASSERT_EQ(a[r].size(), b[r].size());
      EXPECT_NEAR(a[r][c], b[r][c], tolerance * std::max(scale, 1e-30)) << a_file << " row " << r << " column " << c;
    }
  }
}

nlohmann::json run_json(const std::string& dir) {
  std::ifstream in(dir + "/run.json");
  return nlohmann::json::parse(in);
}

// The Krylov solves stop at 1e-10 of the right-hand side and Newton at 1e-10 of the first residual
// (quadratic convergence takes it far below that in its last step), so each run's solution is
// within about cond(J) 1e-10 |x| of the exact discrete one; cond(J) stays below 1e3 on these
// meshes, so 1e-7 of each probe's scale bounds the difference with room (measured: 1e-13 or less).
constexpr double kAgreement = 1e-7;

constexpr const char* kSteadyCavity = R"({"name": "cavity", "settings": {"solver": "fem", "integrator": "steady",
    "gravity": [0, 0, 0], "newton": {"tolerance": 1e-10}, "linear_solver": {"type": "petsc", "tolerance": 1e-10}},
  "objects": [{"name": "fluid", "kind": "fluid", "mesh": {"type": "rectangle", "min": [0, 0], "max": [1, 1], "cells": [32, 32]},
    "density": 1.0, "viscosity": 0.01,
    "boundaries": [{"where": {"side": "top"}, "velocity": ["1", "0"]},
                   {"where": {"side": ["left", "right", "bottom"]}, "type": "no_slip"}],
    "pressure_reference": {"mean": 0}}],
  "probes": [{"name": "vertical_centreline", "type": "line", "from": [0.5, 0], "to": [0.5, 1], "samples": 33},
             {"name": "lid_force", "type": "boundary_force", "where": {"side": "top"}}]})";

TEST_F(MpiRuns, TwoRanksSolveTheSteadyCavityOfOne) {
  const auto [one, two] = run_both("mpi_cavity", kSteadyCavity);
  expect_same_csv(one + "/probes.csv", two + "/probes.csv", kAgreement);
  expect_same_csv(one + "/line_vertical_centreline.csv", two + "/line_vertical_centreline.csv", kAgreement);
  const nlohmann::json run = run_json(two);
  EXPECT_EQ(run["mpi_ranks"], 2);
  EXPECT_EQ(run["status"], "completed");
  // METIS balances the nodes within 3 %; rank 0 assembles about half the cells and a shared layer.
  const auto rows = run["partition"]["rows_per_rank"].get<std::vector<int>>();
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0] + rows[1], run["counts"]["free_unknowns"].get<int>());
  EXPECT_NEAR(rows[0], rows[1], 0.03 * (rows[0] + rows[1]));
  EXPECT_GT(run["partition"]["cells_assembled_by_rank_0"].get<int>(), 32 * 32 / 2);
  EXPECT_LT(run["partition"]["cells_assembled_by_rank_0"].get<int>(), 32 * 32 / 2 + 2 * 33);
  EXPECT_EQ(run_json(one).count("mpi_ranks"), 0u);
}

TEST_F(MpiRuns, TwoRanksFollowTheTransientCavityOfOne) {
  nlohmann::json scene = nlohmann::json::parse(test::kTransientCavity);
  scene["settings"]["duration"] = 0.5;
  scene["settings"]["newton"] = {{"tolerance", 1e-10}};
  scene["settings"]["linear_solver"] = {{"type", "petsc"}, {"tolerance", 1e-10}};
  const auto [one, two] = run_both("mpi_transient", scene.dump());
  expect_same_csv(one + "/probes.csv", two + "/probes.csv", kAgreement);
  EXPECT_EQ(run_json(two)["steps"], 10);
}

TEST_F(MpiRuns, TwoRanksBendTheHexBlockOfOne) {
  constexpr const char* block = R"({"name": "block", "settings": {"solver": "fem", "integrator": "static", "dt": 1,
      "duration": 2, "gravity": [0, 0, 0], "newton": {"tolerance": 1e-10},
      "linear_solver": {"type": "petsc", "tolerance": 1e-10}},
    "objects": [{"name": "b", "kind": "solid", "mesh": {"type": "box", "min": [0, 0, 0], "max": [1, 1, 1], "cells": [6, 6, 6], "element": "hex8"},
      "material": {"model": "neo_hookean", "youngs_modulus": 1e6, "poisson_ratio": 0.3, "density": 1000},
      "loads": [{"type": "traction", "where": {"boundary": "right"}, "value": [0, "-1e4 * t", 0]}],
      "dirichlet": [{"where": {"boundary": "left"}, "value": [0, 0, 0]}]}],
    "probes": [{"name": "corner", "type": "point", "object": "b", "nearest": [1, 1, 1], "quantity": "displacement"}]})";
  const auto [one, two] = run_both("mpi_block", block);
  expect_same_csv(one + "/probes.csv", two + "/probes.csv", kAgreement);
  EXPECT_GT(std::abs(test::read_probes(two).back()[2]), 1e-3) << "the block bends";
  // Each rank assembled about half the 216 cells, and a shared layer.
  const nlohmann::json run = run_json(two);
  const auto rows = run["partition"]["rows_per_rank"].get<std::vector<int>>();
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0] + rows[1], run["counts"]["free_dofs"].get<int>());
  EXPECT_GT(run["partition"]["cells_assembled_by_rank_0"].get<int>(), 216 / 2 - 216 / 10);
  EXPECT_LT(run["partition"]["cells_assembled_by_rank_0"].get<int>(), 216 / 2 + 2 * 36);
}

// The energy-momentum scheme (nonsymmetric tangents, GMRES around GAMG) on a beam set ringing by
// a load that is released: its tip and its total energy, which the scheme conserves once the load
// is gone, follow the run on one process.
TEST_F(MpiRuns, TwoRanksRingTheBeamOfOne) {
  constexpr const char* beam = R"json({"name": "beam", "settings": {"solver": "fem", "dt": 0.02, "duration": 0.2,
      "integrator": "energy_momentum", "gravity": [0, 0, 0], "newton": {"tolerance": 1e-10},
      "linear_solver": {"type": "petsc", "tolerance": 1e-10}},
    "objects": [{"name": "beam", "kind": "solid", "mesh": {"type": "box", "min": [0,0,0], "max": [1,0.1,0.1], "cells": [20,2,2], "element": "hex8"},
      "material": {"model": "neo_hookean", "youngs_modulus": 1e7, "poisson_ratio": 0.3, "density": 1000},
      "loads": [{"type": "nodal_force", "where": {"box": {"min": [0.9,-1,-1], "max": [2,2,2]}}, "value": ["0", "20*(t<0.05)", "0"]}],
      "dirichlet": [{"where": {"boundary": "left"}, "value": [0, 0, 0]}]}],
    "probes": [{"name": "tip", "type": "point", "object": "beam", "nearest": [1, 0.05, 0.05]},
               {"name": "E", "type": "energy", "quantity": "total"}]})json";
  const auto [one, two] = run_both("mpi_beam", beam);
  expect_same_csv(one + "/probes.csv", two + "/probes.csv", kAgreement);
  EXPECT_EQ(run_json(two)["steps"], 10);
  EXPECT_GT(test::read_probes(two).back().back(), 0) << "the load put energy into the beam";
}

// A distributed run stopped with a checkpoint and resumed on the same number of ranks continues
// bit for bit: the probes and the final state (the checkpoint's bytes) are those of the run that
// was not stopped. (The ranks' collective operations and PETSc's parallel preconditioners are
// deterministic for a given number of ranks.)
TEST_F(MpiRuns, TwoRanksResumeFromACheckpointBitForBit) {
  nlohmann::json scene = nlohmann::json::parse(test::kTransientCavity);
  scene["settings"]["duration"] = 0.5;
  scene["settings"]["linear_solver"] = {{"type", "petsc"}};
  const std::string path = test::write_scene("mpi_restart", scene.dump());
  const std::string dir = fs::path(path).parent_path().string();
  const auto run = [](const std::string& arguments) {
    const auto r = run_on_ranks(2, arguments + " --quiet");
    EXPECT_EQ(r.exit_code, 0) << r.output;
  };
  run(fmt::format("run {} --out {}/whole --checkpoint-every 10", path, dir));
  run(fmt::format("run {} --out {}/parts --duration 0.25 --checkpoint-every 5", path, dir));
  run(fmt::format("run {} --restart {}/parts/checkpoint.bin --duration 0.25 --checkpoint-every 5", path, dir));
  // The checkpoints differ only in the output directory their header names, and so in the
  // checksum that ends them (8 bytes).
  std::string whole = test::file_bytes(dir + "/whole/checkpoint.bin"), parts = test::file_bytes(dir + "/parts/checkpoint.bin");
  ASSERT_GT(whole.size(), 100u);
  const size_t named = whole.find(dir + "/whole");
  ASSERT_NE(named, std::string::npos);
  whole.replace(named, dir.size() + 6, dir + "/parts");
  ASSERT_EQ(whole.size(), parts.size());
  EXPECT_TRUE(whole.substr(0, whole.size() - 8) == parts.substr(0, parts.size() - 8)) << "the resumed run's final state differs";
  EXPECT_EQ(test::file_bytes(dir + "/whole/probes.csv"), test::file_bytes(dir + "/parts/probes.csv"));
  EXPECT_EQ(run_json(dir + "/parts")["status"], "completed");
}

TEST_F(MpiRuns, ScenesThatCannotBeDistributedAreBadInput) {
  const auto refused = [](const std::string& path, const std::string& needle) {
    const std::string out = test::temp_dir("mpi_refused") + "/out";
    const auto r = run_on_ranks(2, fmt::format("run {} --out {} --quiet", path, out));
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find(needle), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("moreau: error:"), r.output.rfind("moreau: error:")) << "printed once, by rank 0: " << r.output;
    EXPECT_FALSE(fs::exists(out));
  };
  nlohmann::json direct = nlohmann::json::parse(kSteadyCavity);
  direct["settings"]["linear_solver"] = {{"type", "direct"}};
  refused(test::write_scene("mpi_direct", direct.dump()), "settings.linear_solver.type: this run has 2 MPI ranks");
  refused(test::scene_path("rigid_playground.json"), "settings.solver: \"xpbd\" runs on one process");
}

// Rank 0 alone cannot create the output directory: it reports it and leaves, and the other rank,
// already waiting for rank 0 in the first step, is ended by mpirun instead of waiting for ever.
TEST_F(MpiRuns, AnErrorOfOneRankEndsTheWholeRun) {
  const std::string path = test::write_scene("mpi_one_rank_fails", kSteadyCavity);
  const auto r = run_on_ranks(2, fmt::format("run {} --out /proc/no-such-directory --quiet", path));
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("cannot prepare the output directory"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace moreau
