#pragma once
// Small helpers for tests: scenes from inline JSON, stepping, running the CLI.
#include <fmt/format.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "moreau/scene/scene.hpp"
#include "moreau/solvers/xpbd/xpbd_step.hpp"

namespace moreau::test {

/// A unique temporary directory for one test.
inline std::string temp_dir(const std::string& tag) {
  const auto dir = std::filesystem::temp_directory_path() / fmt::format("moreau-test-{}-{}", tag, getpid());
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir.string();
}

/// Writes `json` to a scene file and loads it.
inline Scene scene_from_json(const std::string& json, const std::vector<std::string>& overrides = {}) {
  const std::string path = temp_dir("scene") + "/scene.json";
  std::ofstream(path) << json;
  return load_scene(path, overrides);
}

/// Steps a constraint-engine scene through its solver (the one settings.solver selects).
inline void run_steps(Scene& scene, long steps) {
  StageTimer timer;
  for (long s = 0; s < steps; ++s)
    scene.formulation->step(scene.model, scene.state, timer, solver_thread_count(scene.model));
}

struct CommandResult {
  int exit_code;
  std::string output;  // stdout and stderr
};

/// Runs the moreau binary with `args`, capturing its output.
inline CommandResult run_moreau(const std::string& args) {
  const std::string log = temp_dir("cli") + "/log.txt";
  const int status = std::system(fmt::format("{} {} > {} 2>&1", MOREAU_BINARY, args, log).c_str());
  std::ifstream in(log);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return {WEXITSTATUS(status), text};
}

}  // namespace moreau::test
