#pragma once
// The fields every run.json has, whichever engine ran the scene.
#include <nlohmann/json.hpp>
#include <string>

namespace moreau {

struct RunSummaryCommon {
  std::string scene, scene_file, solver, status, message;  // message: empty unless the run failed
  double dt = 0, simulated_time_s = 0, wall_time_s = 0;
  int threads = 0;
  long steps = 0;
};

/// moreau_version, scene, scene_file, status, message (if any), solver, dt, threads, steps,
/// simulated_time_s, wall_time_s.
nlohmann::json run_summary_json(const RunSummaryCommon& run);

}  // namespace moreau
