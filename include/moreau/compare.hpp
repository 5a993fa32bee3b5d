#pragma once
// moreau::compare_solvers: one scene run under several constraint-engine formulations (e.g. xpbd
// and nmd) and a report that sets them side by side. What `moreau compare` does.
//
// Each solver's run is a full output directory (DIR/<solver>/: run.json, probes.csv, frames). To
// the scene's own probes the comparison adds its own columns, named "cmp_...": the total energy,
// the largest stretch of the distance rows (when there is cloth), the largest joint error (when
// there are joints) and the deepest contact penetration, in all and per object. DIR/report.md and
// DIR/report.html set out, per solver, the wall time per step, the energy at the start and end and its largest gain, the largest
// constraint error and penetration, and every probe's final value and largest difference from the
// first solver, with a plot of each probe column (DIR/plots/*.svg); DIR/compare.csv holds every
// column of every solver on the shared output times.
#include <optional>
#include <string>
#include <vector>

namespace moreau {

struct CompareOptions {
  std::string scene_path;
  std::vector<std::string> solvers;    // at least two distinct registered formulations
  std::vector<std::string> overrides;  // "path=value", applied to every run
  std::string out_dir;                 // empty: out/<scene name>-compare
  std::optional<double> duration;      // s, overrides settings.duration
  std::optional<int> threads;          // overrides settings.threads (0 = all cores)
  bool progress = false;               // a progress bar per run on stderr
};

struct CompareResult {
  std::string out_dir;
  std::string report_markdown, report_html;  // paths
  std::vector<std::string> failed_solvers;   // runs that stopped on a numerical failure
};

/// Runs the scene under each solver and writes the comparison. Throws InputError for a bad scene,
/// an unknown or repeated solver, or a scene that is not a constraint-engine scene. A solver whose
/// run fails numerically is reported (its output up to the failure) and the others still run.
CompareResult compare_solvers(const CompareOptions& options);

}  // namespace moreau
