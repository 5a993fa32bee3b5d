// The `moreau` command-line program.
//   moreau run SCENE.json [--out DIR] [--duration T] [--threads N] [--quiet] [--set key=value ...]
//              [--checkpoint-every N] [--restart CHECKPOINT]
//   moreau check SCENE.json [--set key=value ...]
//   moreau compare SCENE.json --solvers xpbd,nmd [--out DIR] [--duration T] [--threads N] [--quiet] [--set ...]
//   moreau view OUTPUT_DIR [--port P] [--no-browser]
//   moreau render OUTPUT_DIR [--frame N | --all | --video FILE.mp4] [--out FILE.png] [--colour-by ARRAY] [--size WxH]
// run and check take --memory-limit GB (what a scene's meshes and particles may need).
//   moreau --version | --help
// Exit codes: 0 success, 1 anything else, 2 bad input, 3 numerical failure, 128 + the signal's
// number when SIGINT (130) or SIGTERM (143) stopped a run (after its step, with a checkpoint).
#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>

#include "moreau/app/output_server.hpp"
#include "moreau/fem/distributed/mpi_ranks.hpp"
#include "moreau/app/render_output.hpp"
#include "moreau/moreau.hpp"

namespace {
constexpr int kExitOther = 1, kExitBadInput = 2, kExitNumerical = 3;

// The first SIGINT or SIGTERM asks the run to stop after its current step and write a checkpoint;
// a second one ends the program at once (the default action).
extern "C" void stop_after_step(int signal_number) {
  moreau::request_stop(signal_number);
  std::signal(signal_number, SIG_DFL);
}

// A rank of a distributed run that fails leaves at once, without MPI_Finalize: an error may be
// one rank's alone (rank 0 cannot write the output directory; a file missing on one node), and
// MPI_Finalize would wait for ranks that are waiting for it in the next collective operation.
// mpirun sees the exit code and ends the other ranks.
int leave_distributed_run(int code) {
  if (moreau::mpi_ranks() <= 1) return code;
  std::fflush(stdout);
  std::fflush(stderr);
  std::_Exit(code);
}
}

int main(int argc, char** argv) {
  CLI::App app{"moreau: a multiphysics simulation engine (constraint-based XPBD and finite elements)", "moreau"};
  app.set_version_flag("--version", std::string("moreau ") + moreau::version());
  app.require_subcommand(1);

  std::string scene_path, out_dir;
  std::vector<std::string> overrides;
  double duration = 0, memory_limit_gb = 0;
  int threads = -1;
  bool quiet = false;

  CLI::App* run = app.add_subcommand("run", "run a scene and write its output directory");
  run->add_option("scene", scene_path, "scene file (JSON)")->required();
  run->add_option("--out", out_dir, "output directory (default out/<scene name>)");
  // A finite, positive time: "nan" and "inf" are refused, not ignored.
  const CLI::Validator finite_positive(
      [](std::string& text) {
        double value = 0;
        try {
          size_t used = 0;
          value = std::stod(text, &used);
          if (used != text.size()) return std::string("not a number: " + text);
        } catch (const std::exception&) {
          return std::string("not a number: " + text);
        }
        return std::isfinite(value) && value > 0 ? std::string() : "must be a finite time > 0 s, not " + text;
      },
      "SECONDS > 0");
  run->add_option("--duration", duration, "simulated time in s (overrides settings.duration)")->check(finite_positive);
  run->add_option("--threads", threads,
                  "most worker threads to use (0 = all cores; fewer while other processes keep cores busy; "
                  "overrides settings.threads)")
      ->check(CLI::Range(0, 1024));
  run->add_flag("--quiet", quiet, "no progress bar");
  const auto memory_limit_help = "memory the scene's meshes and particles may need, in GB (default: 80 % of physical memory)";
  const auto positive_gb = CLI::Range(1e-6, 1e9);
  run->add_option("--memory-limit", memory_limit_gb, memory_limit_help)->check(positive_gb);
  run->add_option("--set", overrides, "override a scene value by its JSON path, e.g. --set settings.substeps=40");
  int checkpoint_every = -1;
  std::string restart_path;
  run->add_option("--checkpoint-every", checkpoint_every,
                  "write DIR/checkpoint.bin every N steps and at the end (overrides settings.output.checkpoint_every; 0: "
                  "only when interrupted)")
      ->check(CLI::Range(0, 1 << 30));
  run->add_option("--restart", restart_path,
                  "resume from a checkpoint of this scene; runs what is left of settings.duration (or --duration more) "
                  "and continues the output directory the checkpoint's run wrote (or writes to --out)");

  CLI::App* check = app.add_subcommand("check", "validate a scene and print what it builds");
  check->add_option("scene", scene_path, "scene file (JSON)")->required();
  check->add_option("--set", overrides, "override a scene value by its JSON path");
  check->add_option("--memory-limit", memory_limit_gb, memory_limit_help)->check(positive_gb);

  std::string solver_list;
  CLI::App* compare = app.add_subcommand("compare", "run a scene under several solvers and write a report side by side");
  compare->add_option("scene", scene_path, "scene file (JSON)")->required();
  compare->add_option("--solvers", solver_list, "the solvers to compare, e.g. xpbd,nmd (the first is the reference)")
      ->required();
  compare->add_option("--out", out_dir, "output directory (default out/<scene name>-compare)");
  compare->add_option("--duration", duration, "simulated time in s (overrides settings.duration)")->check(finite_positive);
  compare->add_option("--threads", threads, "most worker threads to use (0 = all cores; overrides settings.threads)")->check(CLI::Range(0, 1024));
  compare->add_flag("--quiet", quiet, "no progress bars");
  compare->add_option("--set", overrides, "override a scene value by its JSON path, for every solver");

  std::string output_dir;
  int port = 0;
  bool no_browser = false;
  CLI::App* view = app.add_subcommand("view", "play a run's output back in the browser (served on this machine only)");
  view->add_option("output", output_dir, "a run's output directory, e.g. out/showcase")->required();
  view->add_option("--port", port, "port on 127.0.0.1 (default: any free one)")->check(CLI::Range(0, 65535));
  view->add_flag("--no-browser", no_browser, "only print the page's address");

  moreau::RenderOptions render_options;
  std::string size;
  CLI::App* render = app.add_subcommand("render", "draw a run's frames as PNG (or an MP4) without a display, in headless Chromium");
  render->add_option("output", render_options.output_dir, "a run's output directory, e.g. out/showcase")->required();
  auto* frame_option = render->add_option("--frame", render_options.frame, "the frame to draw: 0 is the first (default: the last)")
                           ->check(CLI::Range(0, 1 << 30));
  auto* all_option = render->add_flag("--all", render_options.all_frames, "every frame, as DIR/render/<scene>_NNNNNN.png");
  auto* video_option = render->add_option("--video", render_options.video, "every frame, encoded into this MP4 at 30 frames/s (needs ffmpeg)");
  frame_option->excludes(all_option)->excludes(video_option);
  render->add_option("--out", render_options.out, "the PNG of the one frame (default DIR/render/<scene>_NNNNNN.png)")->excludes(all_option)->excludes(video_option);
  render->add_option("--colour-by", render_options.colour_by, "a point array to colour by, e.g. velocity (default: each object in its colour)");
  render->add_option("--size", size, "picture size in pixels, WIDTHxHEIGHT (default 1280x720)");
  render->add_flag("--quiet", quiet, "print nothing on success");

  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return kExitBadInput;
  }

  // Under mpirun (a distributed FEM run) MPI starts first, in the PETSc plugin; every rank then
  // runs the same program on the same scene, and rank 0 alone prints and writes.
  try {
    moreau::start_mpi_if_launched();
  } catch (const std::exception& e) {
    fmt::print(stderr, "moreau: error: this process was started by mpirun, but MPI cannot start: {}\n", e.what());
    return kExitOther;
  }
  const bool root = moreau::mpi_rank() == 0;
  if (!root) quiet = true;
  const auto rank_prefix = [] { return moreau::mpi_ranks() > 1 ? fmt::format("[rank {}] ", moreau::mpi_rank()) : std::string(); };

  try {
    if (memory_limit_gb > 0) moreau::set_memory_limit(memory_limit_gb * 1e9);
    if (view->parsed()) {
      moreau::view_output(output_dir, port, !no_browser);
      return 0;
    }
    if (render->parsed()) {
      if (!size.empty()) {
        char x = 0;
        std::istringstream in(size);
        if (!(in >> render_options.width >> x >> render_options.height) || x != 'x' || !in.eof())
          throw moreau::InputError(fmt::format("--size {}: expected WIDTHxHEIGHT in pixels, e.g. 1280x720", size));
      }
      const std::string written = moreau::render_output(render_options);
      if (!quiet) fmt::print("moreau: rendered {}\n", written);
      return 0;
    }
    if (compare->parsed()) {
      moreau::CompareOptions options;
      options.scene_path = scene_path;
      for (size_t start = 0; start <= solver_list.size();) {
        const size_t comma = std::min(solver_list.find(',', start), solver_list.size());
        options.solvers.push_back(solver_list.substr(start, comma - start));
        start = comma + 1;
      }
      options.overrides = overrides;
      options.out_dir = out_dir;
      if (duration > 0) options.duration = duration;
      if (threads >= 0) options.threads = threads;
      options.progress = !quiet && isatty(STDERR_FILENO);
      const moreau::CompareResult r = moreau::compare_solvers(options);
      for (const std::string& s : r.failed_solvers)
        fmt::print(stderr, "moreau: the '{}' run failed numerically; the report shows it up to the failure\n", s);
      if (!quiet) fmt::print("moreau: comparison written to {} (and {})\n", r.report_html, r.report_markdown);
      return r.failed_solvers.empty() ? 0 : kExitNumerical;
    }
    moreau::World world = moreau::World::load(scene_path, overrides);
    if (check->parsed()) {
      if (root) fmt::print("{}scene is valid\n", world.summary());
      return 0;
    }
    if (!restart_path.empty()) world.restore(restart_path);
    moreau::RunOptions options;
    options.out_dir = out_dir;
    if (duration > 0) options.duration = duration;
    if (threads >= 0) options.threads = threads;
    if (checkpoint_every >= 0) options.checkpoint_every = checkpoint_every;
    options.progress = !quiet && isatty(STDERR_FILENO);
    std::signal(SIGINT, stop_after_step);
    std::signal(SIGTERM, stop_after_step);
    const moreau::RunResult r = world.run(options);
    if (r.stopped_by_signal != 0 && !root) return 128 + r.stopped_by_signal;
    if (r.stopped_by_signal != 0) {
      std::string resume = (moreau::mpi_ranks() > 1 ? fmt::format("mpirun -np {} ", moreau::mpi_ranks()) : std::string()) +
                           "moreau run " + scene_path;
      for (const std::string& o : overrides) resume += " --set '" + o + "'";
      if (!out_dir.empty()) resume += " --out " + out_dir;
      fmt::print(stderr, "moreau: stopped by {} at t = {:.6g} s after {} steps; checkpoint {}\nmoreau: resume with: {} --restart {}\n",
                 r.stopped_by_signal == SIGINT ? "SIGINT" : r.stopped_by_signal == SIGTERM ? "SIGTERM" : "a signal",
                 world.time(), world.steps(), r.checkpoint, resume, r.checkpoint);
      return 128 + r.stopped_by_signal;
    }
    if (!quiet)
      fmt::print("moreau: '{}' ran {} steps in {:.3f} s ({:.1f} steps/s); output in {}/\n", world.name(), r.steps,
                 r.wall_time_s, r.steps / std::max(r.wall_time_s, 1e-12), r.out_dir);
    return 0;
  } catch (const moreau::InputError& e) {
    // Every rank reads the same scene and takes the same decisions: rank 0 speaks for all.
    if (root) fmt::print(stderr, "moreau: error: {}\n", e.what());
    return leave_distributed_run(kExitBadInput);
  } catch (const moreau::NumericalError& e) {
    if (root) fmt::print(stderr, "moreau: numerical failure: {}\n", e.what());
    return leave_distributed_run(kExitNumerical);
  } catch (const std::exception& e) {
    fmt::print(stderr, "moreau: {}internal error: {}\n", rank_prefix(), e.what());
    return leave_distributed_run(kExitOther);
  }
}
