#pragma once
// The runs of a comparison: the scene under each solver, to its own output directory, with the
// comparison's probes added, and what each run measured read back.
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "moreau/compare.hpp"

namespace moreau {

struct SolverRun {
  std::string solver;
  std::string status = "completed", message;  // "failed" and the numerical failure's message
  std::string out_dir;
  long steps = 0;
  double wall_time_s = 0;                     // the stepping loop
  std::map<std::string, double> stage_times;  // s
  std::vector<std::string> columns;           // probes.csv's columns after time
  std::vector<double> time;                   // s, one per output row
  std::vector<std::vector<double>> values;    // per column, one per output row
};

/// The columns the comparison adds to every run (all of them start with kComparisonPrefix).
inline constexpr const char* kComparisonPrefix = "cmp_";
/// After the prefix, the per-object penetration columns' start: cmp_penetration_<object>.
inline constexpr std::string_view kPenetrationOf = "penetration_";

struct SolverRuns {
  std::string scene_name;
  std::string out_dir;        // options.out_dir, or out/<scene name>-compare; prepared for writing
  std::vector<SolverRun> runs;
};

/// Loads (and so validates) the scene for every solver, then runs it under each of
/// options.solvers into <out_dir>/<solver>/.
SolverRuns run_each_solver(const CompareOptions& options);

/// A run's probes.csv: its columns after time and its rows.
void read_probe_table(const std::string& path, SolverRun& run);

}  // namespace moreau
