#pragma once
// The public C++ API of moreau: load a scene, inspect it, step it or run it to an output
// directory. The command-line program, tests and benchmarks all go through this.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "moreau/errors.hpp"

namespace moreau {

/// The version string, e.g. "0.1.0".
const char* version();

/// The memory a scene's meshes and particles may need, in bytes, checked when a scene is loaded
/// (a larger scene is an InputError naming the key). Default: 80 % of the physical memory.
void set_memory_limit(double bytes);

struct RunOptions {
  std::string out_dir;                 // empty: out/<scene name>
  std::optional<double> duration;      // s, overrides settings.duration
  std::optional<int> threads;          // overrides settings.threads (0 = all cores)
  bool progress = false;               // draw a progress bar on stderr
};

struct RunResult {
  long steps = 0;
  double wall_time_s = 0;              // the stepping loop only
  std::string out_dir;
};

struct Scene;
class Engine;

class Simulation {
 public:
  /// Loads and validates a scene file; `overrides` are "path=value" assignments (--set).
  /// Throws InputError on bad input. Nothing is written.
  static Simulation load(const std::string& scene_path, const std::vector<std::string>& overrides = {});
  ~Simulation();
  Simulation(Simulation&&) noexcept;
  Simulation& operator=(Simulation&&) noexcept;

  /// A human-readable account of what the scene builds (objects, particles, constraints, colours).
  std::string summary() const;
  const std::string& name() const;

  /// Runs the scene from its initial state and writes the output directory (run.json,
  /// probes.csv, <scene>.pvd, frames/). Throws NumericalError if the simulation fails; the
  /// output written so far (and run.json with "status": "failed") remains.
  RunResult run(const RunOptions& options);

  /// Lower-level access for tests and embedding: advance one step of settings.dt (any engine).
  /// Throws NumericalError if it fails.
  void step();
  double time() const;
  /// Current position of a particle of the named object (m).
  std::vector<double> position(const std::string& object, int vertex) const;

  /// The scene's internals (model, state); only for moreau's own tests and benchmarks.
  Scene& internals();

 private:
  explicit Simulation(std::unique_ptr<Scene> scene);
  std::unique_ptr<Scene> scene_;
  std::unique_ptr<Engine> engine_;  // steps scene_'s model and state
};

}  // namespace moreau
