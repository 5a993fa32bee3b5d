// moreau::compare_solvers (include/moreau/compare.hpp): the runs, then the report.
#include "moreau/compare.hpp"

#include "moreau/compare/comparison_report.hpp"
#include "moreau/compare/solver_runs.hpp"

namespace moreau {

CompareResult compare_solvers(const CompareOptions& options) {
  const SolverRuns runs = run_each_solver(options);
  CompareResult result;
  result.out_dir = runs.out_dir;
  std::tie(result.report_markdown, result.report_html) =
      write_comparison_report({runs.scene_name, options.scene_path, runs.out_dir}, runs.runs);
  for (const SolverRun& run : runs.runs)
    if (run.status != "completed") result.failed_solvers.push_back(run.solver);
  return result;
}

}  // namespace moreau
