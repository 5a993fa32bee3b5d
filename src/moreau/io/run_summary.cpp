#include "moreau/io/run_summary.hpp"

#include "moreau/moreau.hpp"

namespace moreau {

nlohmann::json run_summary_json(const RunSummaryCommon& run) {
  nlohmann::json j;
  j["moreau_version"] = version();
  j["scene"] = run.scene;
  j["scene_file"] = run.scene_file;
  j["status"] = run.status;
  if (!run.message.empty()) j["message"] = run.message;
  j["solver"] = run.solver;
  j["dt"] = run.dt;
  j["threads"] = run.threads;
  j["steps"] = run.steps;
  j["simulated_time_s"] = run.simulated_time_s;
  j["wall_time_s"] = run.wall_time_s;
  return j;
}

}  // namespace moreau
