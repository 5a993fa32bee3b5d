#pragma once
// The one run loop: steps any engine to the scene's duration and writes its output directory.
#include <string>

#include "moreau/run/checkpoint.hpp"
#include "moreau/world.hpp"

namespace moreau {

class Engine;
struct Scene;

/// A checkpoint a World was restored from: the next run continues its output directory.
struct RestartPoint {
  std::string path;
  CheckpointHeader header;
};

/// What the run loop needs to know of the World it runs.
struct RunContext {
  const CheckpointHeader& identity;  // the scene as its checkpoints identify it
  const RestartPoint* restart;       // the checkpoint the state was restored from (null: none)
  long& steps_taken;                 // steps from the scene's start; counts every step that completes
};

/// Steps `engine` from its current state for options.duration (default: the scene's, less what a
/// restored checkpoint had simulated), sampling the probes and writing frames every output.every
/// steps from the scene's start (and after the last), checkpoints every checkpoint_every steps
/// (and at the end), then writes run.json. The step's thread count is the requested one
/// (options.threads, else settings.threads) less the cores other processes keep busy. A run
/// restored from a checkpoint whose output directory is this run's continues it (frames,
/// probes.csv, rigid_poses.csv and the .pvd are cut back to the checkpoint, then extended).
/// Throws NumericalError if a step fails; what was written so far stays, with "status": "failed"
/// in run.json. After request_stop it stops after the current step, writes a checkpoint and
/// run.json with "status": "interrupted", and returns.
RunResult run_engine(Engine& engine, const Scene& scene, const RunOptions& options, const RunContext& context);

}  // namespace moreau
