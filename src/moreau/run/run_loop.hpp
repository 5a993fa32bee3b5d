#pragma once
// The one run loop: steps any engine to the scene's duration and writes its output directory.
#include "moreau/world.hpp"

namespace moreau {

class Engine;
struct Scene;

/// Steps `engine` from its current state for options.duration (default: the scene's), sampling
/// the probes and writing frames every output.every steps (and after the last), then writes
/// run.json. The step's thread count is the requested one (options.threads, else settings.threads)
/// less the cores other processes keep busy. Throws NumericalError if a step fails; what was
/// written so far stays, with "status": "failed" in run.json. `steps_taken` counts every step
/// that completed, also when the run fails.
RunResult run_engine(Engine& engine, const Scene& scene, const RunOptions& options, long& steps_taken);

}  // namespace moreau
