#include "moreau/run/run_loop.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <chrono>
#include <filesystem>
#include <fstream>

#include "moreau/io/frame_writer.hpp"
#include "moreau/io/output_budget.hpp"
#include "moreau/io/probe_csv.hpp"
#include "moreau/io/progress_bar.hpp"
#include "moreau/io/run_summary.hpp"
#include "moreau/run/engine.hpp"
#include "moreau/scene/scene.hpp"
#include "moreau/solvers/thread_budget.hpp"

namespace moreau {

RunResult run_engine(Engine& engine, const Scene& scene, const RunOptions& options, long& steps_taken) {
  const int requested_threads = options.threads.value_or(engine.requested_threads());
  const int threads = requested_threads > 0 ? requested_threads : omp_get_max_threads();
  const double duration = options.duration.value_or(scene.duration);
  const bool solves_once = engine.dt() == 0;
  const long steps = solves_once ? 1 : run_step_count(duration, engine.dt());
  const auto started = std::filesystem::file_time_type::clock::now();

  RunResult result;
  result.out_dir = run_output_directory(options.out_dir, scene.name);
  engine.open_frames(result.out_dir, scene.name);
  ProbeCsv csv(result.out_dir, engine.probe_columns());
  std::vector<Real> values;
  auto sample = [&] {
    values.clear();
    engine.sample_probes(values);
    csv.write_row(engine.time(), values);
    if (scene.output.write_vtk) engine.write_frame();
  };

  ProgressBar progress(options.progress && !solves_once, duration);
  if (!solves_once) {
    sample();
    csv.flush();
    check_output_budget(result.out_dir, steps, scene.output.every, started);
  }
  double wall = 0;
  std::string status = "completed", message;
  // The requested thread count is a maximum: cores that other processes keep busy are left to them.
  ThreadBudget budget(requested_threads);
  try {
    for (long s = 0; s < steps; ++s) {
      const int step_threads = budget.next_step_threads();
      const auto t0 = std::chrono::steady_clock::now();
      try {
        engine.step(step_threads);
      } catch (...) {
        wall += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        throw;
      }
      wall += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      result.steps = s + 1;
      ++steps_taken;
      if ((s + 1) % scene.output.every == 0 || s + 1 == steps) sample();
      progress.update(engine.time(), result.steps, wall);
    }
  } catch (const NumericalError& e) {
    status = "failed";
    message = e.what();
  }
  progress.finish();
  for (const std::string& w : engine.warnings()) fmt::print(stderr, "warning: {}\n", w);
  engine.write_final_output(result.out_dir);
  result.wall_time_s = wall;

  nlohmann::json j = run_summary_json({scene.name, scene.file, scene.solver, status, message, engine.dt(),
                                       engine.time(), wall, threads, result.steps});
  engine.add_run_fields(j, status == "completed");
  std::ofstream(result.out_dir + "/run.json") << j.dump(2) << '\n';
  if (status != "completed") throw NumericalError(message);
  return result;
}

}  // namespace moreau
