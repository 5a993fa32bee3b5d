#pragma once
// The comparison's report: report.md and report.html (the same tables; the HTML holds its plots
// inline, the Markdown links plots/*.svg), and compare.csv with every run's columns side by side.
#include <string>
#include <vector>

#include "moreau/compare/solver_runs.hpp"

namespace moreau {

struct ComparisonSubject {
  std::string scene_name, scene_file, out_dir;
};

/// Writes the report files into subject.out_dir; returns the paths of report.md and report.html.
std::pair<std::string, std::string> write_comparison_report(const ComparisonSubject& subject,
                                                            const std::vector<SolverRun>& runs);

}  // namespace moreau
