// `moreau compare`: one scene under two solvers, side by side. The penetration it reports is
// checked against the contact compliance's law, its tables and compare.csv against each run's own
// probes.csv, and its refusals of what it cannot compare.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "moreau/compare/solver_runs.hpp"
#include "test_helpers.hpp"

namespace moreau {
namespace {

namespace fs = std::filesystem;

// A 1000 kg unit cube resting on the ground from the start, and its height as a probe.
std::string resting_box_scene(const std::string& dir) {
  const std::string path = dir + "/resting_box.json";
  std::ofstream(path) << R"({"name": "resting_box", "settings": {"duration": 1.0, "dt": 0.016666666666666666},
    "objects": [
      {"name": "ground", "kind": "collider", "shape": {"type": "plane"}},
      {"name": "box", "kind": "rigid_body", "shape": {"type": "box", "size": [1, 1, 1]},
       "position": [0, 0.5, 0], "density": 1000}],
    "probes": [{"name": "box", "type": "position", "object": "box"}]})";
  return path;
}

SolverRun read_run(const std::string& csv) {
  SolverRun run;
  read_probe_table(csv, run);
  return run;
}

TEST(Compare, RestingBoxSinksByTheContactComplianceUnderNmdAndNotUnderXpbd) {
  // Under nmd each of the four corner rows at rest holds C = -eps F with F = m g / 4 (SPOOK's
  // stationary point, S lambda = -a C), so the box overlaps the ground by eps m g / 4 =
  // 1e-7 m/N * 1000 kg * 9.81 m/s^2 / 4 = 0.24525 mm. One box's four points share its weight
  // evenly by symmetry, so Gauss-Seidel has nothing left to converge after 1 s: 1e-4 relative
  // (measured 1e-13) leaves room only for round-off and the last of the settling. XPBD's contacts have zero
  // compliance and are projected out at every substep: what remains at the end of a step is the
  // last substep's fall, g (h/n)^2 = 9.81 * (1/60/20)^2 = 6.8e-6 m at most (measured 1e-9 m).
  const std::string dir = test::temp_dir("compare_box");
  const std::string out = dir + "/cmp";
  const test::CommandResult r = test::run_moreau(fmt::format("compare {} --solvers xpbd,nmd --out {} --quiet", resting_box_scene(dir), out));
  ASSERT_EQ(r.exit_code, 0) << r.output;

  const SolverRun xpbd = read_run(out + "/xpbd/probes.csv"), nmd = read_run(out + "/nmd/probes.csv");
  auto last = [](const SolverRun& run, const std::string& column) {
    const auto it = std::find(run.columns.begin(), run.columns.end(), column);
    EXPECT_NE(it, run.columns.end()) << column;
    return run.values[it - run.columns.begin()].back();
  };
  const double expected = 1e-7 * 1000 * 9.81 / 4;
  EXPECT_NEAR(last(nmd, "cmp_penetration_box"), expected, 1e-4 * expected);
  EXPECT_NEAR(last(nmd, "cmp_penetration"), expected, 1e-4 * expected);
  EXPECT_LT(last(xpbd, "cmp_penetration_box"), 6.9e-6);
  // The box's centre sits as deep as its corners.
  EXPECT_NEAR(last(nmd, "box.y"), 0.5 - expected, 1e-4 * expected);
  // Energy at the start: m g y of the centre at 0.5 m (nothing moves yet), the same for both.
  EXPECT_NEAR(xpbd.values[std::find(xpbd.columns.begin(), xpbd.columns.end(), "cmp_energy") - xpbd.columns.begin()][0],
              1000 * 9.81 * 0.5, 1e-9 * 4905);
}

TEST(Compare, ItsTablesRepeatEachRunsProbesExactly) {
  const std::string dir = test::temp_dir("compare_tables");
  const std::string out = dir + "/cmp";
  const test::CommandResult r =
      test::run_moreau(fmt::format("compare {} --solvers nmd,xpbd --out {} --duration 0.25 --quiet", resting_box_scene(dir), out));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const char* file : {"report.md", "report.html", "compare.csv", "nmd/run.json", "xpbd/run.json"})
    EXPECT_TRUE(fs::exists(out + "/" + file)) << file;

  // compare.csv: each run's columns, value for value (17 significant digits both ways).
  const SolverRun merged = read_run(out + "/compare.csv");
  for (const char* solver : {"nmd", "xpbd"}) {
    const SolverRun run = read_run(fmt::format("{}/{}/probes.csv", out, solver));
    EXPECT_EQ(merged.time, run.time);
    for (size_t c = 0; c < run.columns.size(); ++c) {
      const auto it = std::find(merged.columns.begin(), merged.columns.end(), run.columns[c] + "@" + solver);
      ASSERT_NE(it, merged.columns.end()) << run.columns[c];
      EXPECT_EQ(merged.values[it - merged.columns.begin()], run.values[c]) << run.columns[c];
    }
  }
  // The first solver named is the reference the differences are taken from, and each run's wall
  // time per step is its run.json's.
  std::ifstream md_file(out + "/report.md");
  const std::string md((std::istreambuf_iterator<char>(md_file)), std::istreambuf_iterator<char>());
  EXPECT_NE(md.find("largest \\|`xpbd` − `nmd`\\|"), std::string::npos) << md;
  const nlohmann::json run_json = nlohmann::json::parse(std::ifstream(out + "/nmd/run.json"));
  const double ms = 1e3 * run_json["wall_time_s"].get<double>() / run_json["steps"].get<double>();
  EXPECT_NE(md.find(fmt::format("| wall time per step (ms) | {:.3g} |", ms)), std::string::npos) << md;
  EXPECT_TRUE(fs::exists(out + "/plots/00_box.x.svg"));
}

TEST(Compare, WhatItCannotCompareIsBadInputAndNothingIsWritten) {
  const std::string dir = test::temp_dir("compare_bad");
  const std::string scene = resting_box_scene(dir), out = dir + "/cmp";
  auto expect_bad = [&](const std::string& args, const std::string& message) {
    const test::CommandResult r = test::run_moreau(fmt::format("compare {} --out {} --quiet {}", scene, out, args));
    EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.output;
    EXPECT_NE(r.output.find(message), std::string::npos) << args << "\n" << r.output;
    EXPECT_FALSE(fs::exists(out)) << args;
  };
  expect_bad("--solvers xpbd", "give at least two of");
  expect_bad("--solvers xpbd,xpbd", "'xpbd' is given twice");
  expect_bad("--solvers xpbd,pbd", "'pbd' is not a constraint-engine solver; allowed: xpbd, nmd");
  expect_bad("--solvers xpbd,nmd --set probes.box.name=cmp_energy", "the name 'cmp_energy' is one moreau compare adds");
  const std::string fem = std::string(MOREAU_SOURCE_DIR) + "/scenes/fem_beam.json";
  const test::CommandResult r = test::run_moreau(fmt::format("compare {} --solvers xpbd,nmd --out {} --quiet", fem, out));
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("moreau compare runs constraint-engine scenes"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace
}  // namespace moreau
