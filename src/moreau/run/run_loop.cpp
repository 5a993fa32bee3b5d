#include "moreau/run/run_loop.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <optional>

#include "moreau/fem/distributed/mpi_ranks.hpp"
#include "moreau/io/atomic_file.hpp"
#include "moreau/io/frame_writer.hpp"
#include "moreau/io/output_budget.hpp"
#include "moreau/io/probe_csv.hpp"
#include "moreau/io/progress_bar.hpp"
#include "moreau/io/run_summary.hpp"
#include "moreau/run/engine.hpp"
#include "moreau/scene/scene.hpp"
#include "moreau/solvers/thread_budget.hpp"

namespace moreau {

namespace {

namespace fs = std::filesystem;

// The signal request_stop was called with (0: none). A lock-free atomic is async-signal-safe.
std::atomic<int> stop_signal{0};
static_assert(std::atomic<int>::is_always_lock_free);

// Files a run appends rows to (the checkpoint records their sizes, and a restart cuts them back).
constexpr const char* kAppendedFiles[] = {"probes.csv", "rigid_poses.csv"};

std::vector<std::pair<std::string, std::uint64_t>> appended_file_sizes(const std::string& dir) {
  std::vector<std::pair<std::string, std::uint64_t>> sizes;
  for (const char* name : kAppendedFiles) {
    std::error_code ec;
    const auto size = fs::file_size(fs::path(dir) / name, ec);
    if (!ec) sizes.emplace_back(name, size);
  }
  return sizes;
}

bool same_directory(const std::string& a, const std::string& b) {
  std::error_code ec;
  return fs::equivalent(a, b, ec);
}

}  // namespace

void request_stop(int signal_number) { stop_signal.store(signal_number, std::memory_order_relaxed); }

RunResult run_engine(Engine& engine, const Scene& scene, const RunOptions& options, const RunContext& context) {
  // A distributed run's ranks share the cores: one thread each unless the user asks for more.
  const int scene_threads = engine.requested_threads() == 0 && mpi_ranks() > 1 ? 1 : engine.requested_threads();
  const int requested_threads = options.threads.value_or(scene_threads);
  const int threads = requested_threads > 0 ? requested_threads : omp_get_max_threads();
  const bool solves_once = engine.dt() == 0;
  const RestartPoint* restart = solves_once ? nullptr : context.restart;
  long steps = 1;
  if (!solves_once && restart && !options.duration)
    steps = std::max(0L, run_step_count(scene.duration, engine.dt()) - context.steps_taken);
  else if (!solves_once)
    steps = run_step_count(options.duration.value_or(scene.duration), engine.dt());
  const double duration = steps * engine.dt();
  const int checkpoint_every = options.checkpoint_every.value_or(scene.output.checkpoint_every);
  const auto started = fs::file_time_type::clock::now();

  // In a distributed run every rank holds the whole state, and rank 0 alone writes the output.
  const bool writes_output = mpi_rank() == 0;
  RunResult result;
  // Without --out, a restart continues the directory the checkpoint's run wrote, if it is still there.
  std::string out_dir = options.out_dir;
  if (out_dir.empty() && restart && fs::is_directory(restart->header.out_dir)) out_dir = restart->header.out_dir;
  result.out_dir = output_directory_path(out_dir, scene.name);
  const bool continuing = restart && same_directory(restart->header.out_dir, result.out_dir);
  std::optional<ProbeCsv> csv;
  if (writes_output) {
    if (continuing) {
      writable_directory(result.out_dir);
      resume_output_directory(result.out_dir, restart->header.frames, restart->header.appended_files);
    } else {
      result.out_dir = run_output_directory(out_dir, scene.name);
    }
    engine.open_frames(result.out_dir, scene.name, continuing ? restart->header.frames : FrameSeries{});
    csv.emplace(result.out_dir, engine.probe_columns(), continuing);
  }
  std::vector<Real> values;
  auto sample = [&] {
    if (!writes_output) return;
    values.clear();
    engine.sample_probes(values);
    csv->write_row(engine.time(), values);
    if (scene.output.formats.any()) engine.write_frame();
  };
  auto checkpoint = [&] {
    if (!writes_output) return;
    csv->flush();
    CheckpointHeader header = context.identity;
    header.time = engine.time();
    header.steps = context.steps_taken;
    header.out_dir = fs::absolute(result.out_dir).lexically_normal().string();
    header.frames = engine.frame_series();
    header.appended_files = appended_file_sizes(result.out_dir);
    result.checkpoint = result.out_dir + "/checkpoint.bin";
    write_checkpoint(result.checkpoint, header, engine);
  };

  ProgressBar progress(options.progress && !solves_once && writes_output, duration);
  if (!solves_once && !continuing && writes_output) {
    sample();
    csv->flush();
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
      const long step = ++context.steps_taken;  // from the scene's start: the cadence survives a restart
      const bool last = s + 1 == steps;
      if (step % scene.output.every == 0 || last) sample();
      const bool checkpointed = checkpoint_every > 0 && (step % checkpoint_every == 0 || last);
      if (checkpointed) checkpoint();
      progress.update(engine.time(), result.steps, wall);
      // Stopped by a signal: no extra sample, so that the resumed run's output is the uninterrupted one's.
      // In a distributed run all ranks stop at the same step, when any of them was signalled.
      if (const int signal = largest_over_ranks(stop_signal.exchange(0)); signal != 0 && !last) {
        result.stopped_by_signal = signal;
        status = "interrupted";
        message = fmt::format("stopped by signal {} after step {} (t = {:.9g} s)", signal, step, engine.time());
        if (!checkpointed) checkpoint();
        break;
      }
    }
  } catch (const NumericalError& e) {
    status = "failed";
    message = e.what();
  }
  progress.finish();
  result.wall_time_s = wall;
  if (!writes_output) {
    if (status == "failed") throw NumericalError(message);
    return result;
  }
  for (const std::string& w : engine.warnings()) fmt::print(stderr, "warning: {}\n", w);
  if (status != "interrupted") engine.write_final_output(result.out_dir);

  nlohmann::json j = run_summary_json({scene.name, scene.file, scene.solver, status, message, engine.dt(),
                                       engine.time(), wall, threads, result.steps});
  if (!result.checkpoint.empty()) j["checkpoint"] = "checkpoint.bin";
  if (restart)
    j["restarted_from"] = {{"checkpoint", restart->path}, {"time", restart->header.time}, {"step", restart->header.steps}};
  if (mpi_ranks() > 1) j["mpi_ranks"] = mpi_ranks();
  engine.add_run_fields(j, status == "completed");
  write_file_atomically(result.out_dir + "/run.json", j.dump(2) + '\n');
  if (status == "failed") throw NumericalError(message);
  return result;
}

}  // namespace moreau
