#pragma once
// moreau::World: a scene loaded from a file or from JSON text, stepped by whichever engine the
// scene needs (the constraint engine's solver, FEM solids, or the Navier-Stokes flow), with its
// state readable and writable as arrays of doubles between steps. The command line, the tests of
// whole scenes and the benchmarks go through it; it is what the Python module wraps.
//
// Units are SI throughout. State arrays are views into the engine's own storage: no copies, valid
// until the World is destroyed or moved.
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "moreau/errors.hpp"

namespace moreau {

struct RunOptions {
  std::string out_dir;                 // empty: out/<scene name>
  std::optional<double> duration;      // s to run from the current state; default: settings.duration,
                                       // less the time already simulated after World::restore
  std::optional<int> threads;          // overrides settings.threads (0 = all cores)
  std::optional<int> checkpoint_every; // steps between checkpoints; overrides settings.output.checkpoint_every (0: none)
  bool progress = false;               // draw a progress bar on stderr
};

struct RunResult {
  long steps = 0;                      // steps this run took
  double wall_time_s = 0;              // the stepping loop only
  std::string out_dir;
  int stopped_by_signal = 0;           // the signal (SIGINT, SIGTERM) that stopped the run early; 0 if none
  std::string checkpoint;              // the last checkpoint written (out_dir/checkpoint.bin); empty if none
};

/// Asks every run in progress (World::run) to stop after its current step, write a checkpoint and
/// a run.json with "status": "interrupted", and return with RunResult::stopped_by_signal set.
/// Async-signal-safe: the command line calls it from its SIGINT and SIGTERM handlers.
void request_stop(int signal_number);

/// One array of the current state: `count` items of `components` doubles each, item-major
/// (x0 y0 z0 x1 y1 z1 ...). See World::arrays for the names each engine offers.
struct StateArray {
  std::string name;                    // e.g. "particle.position"
  std::string unit;                    // e.g. "m", "m/s", "" (dimensionless)
  int components = 0;
  long count = 0;
  std::span<double> values;            // components * count doubles
  bool writable = false;               // a step reads it, so writing it between steps steers the run
};

/// What a scene object became: its kind and where its items sit in the state arrays.
struct WorldObject {
  std::string name;
  std::string kind;                    // "cloth", "soft_body", "rigid_body", "fluid", "collider", "solid", ...
  long first = 0, count = 0;           // items in the kind's arrays: particles, bodies, or fluid phase
                                       // particles (count only; fluid particles are sorted in space)
};

struct Scene;
class Engine;
struct RestartPoint;
struct CheckpointHeader;

class World {
 public:
  /// Loads and validates a scene file; `overrides` are "path=value" assignments (the CLI's --set).
  /// Throws InputError (file, JSON path, what is allowed) on bad input. Nothing is written.
  static World load(const std::string& scene_path, const std::vector<std::string>& overrides = {});
  /// The same for scene JSON text (e.g. a Python dict dumped to JSON); relative mesh paths are
  /// resolved against the working directory. A constraint-engine scene can also be built object
  /// by object with SceneBuilder (scene_builder.hpp).
  static World from_json(const std::string& scene_json, const std::vector<std::string>& overrides = {});
  ~World();
  World(World&&) noexcept;
  World& operator=(World&&) noexcept;

  const std::string& name() const;
  /// The engine that steps the scene: the constraint solver's name ("xpbd"), "fem" or "flow".
  std::string engine() const;
  /// A human-readable account of what the scene builds (objects, particles, constraints, colours).
  std::string summary() const;
  std::vector<WorldObject> objects() const;

  double time() const;                 // s
  double dt() const;                   // s, one step (0 for a steady flow, which solves once)
  long steps() const;                  // steps from the scene's start (those of a restored checkpoint included)

  /// Advances one step of dt on settings.threads threads (or `threads`; results do not depend on
  /// the count). Throws NumericalError naming the step, the time and the object; the state is
  /// then what the failed step left (to inspect, not to continue from).
  void step();
  void step(int threads);

  /// Runs the scene from its current state to the scene's duration and writes the output
  /// directory (run.json, probes.csv, <scene>.pvd, frames/). Throws NumericalError if a step
  /// fails; the output written so far (and run.json with "status": "failed") remains.
  RunResult run(const RunOptions& options);

  /// The arrays of the current state. By engine:
  ///   constraint engine  particle.position (m), particle.velocity (m/s): cloth, soft-body,
  ///                      granular and shape-matched particles in object order
  ///                      (WorldObject::first/count); particle.angular_velocity (rad/s, world
  ///                      frame): a grain's spin (xpbd turns grains; 0 for particles that do
  ///                      not turn, which ignore what is written there);
  ///                      body.position (m), body.orientation (unit quaternion x y z w),
  ///                      body.velocity (m/s), body.angular_velocity (rad/s, world frame);
  ///                      fluid.position (m, read only: the neighbour lists are kept across
  ///                      steps), fluid.velocity (m/s), fluid.density (kg/m^3, read only) and
  ///                      fluid.pressure (Pa, read only) of the live fluid particles, in the
  ///                      order of a space-filling curve that changes when the lists are rebuilt
  ///   fem                solid.displacement (m), solid.velocity (m/s) per node, dim components;
  ///                      body.director_state: x, d1, d2, d3, v, v_d1, v_d2, v_d3 (24 values)
  ///   flow               flow.solution per node: the velocity (m/s, dim components) then the
  ///                      pressure (Pa)
  std::vector<StateArray> arrays();
  /// One array by name; throws InputError naming the ones there are. Writing a writable array
  /// changes the state the next step starts from (a controller, a prescribed velocity).
  StateArray array(const std::string& name);

  /// Writes a checkpoint of the current state to `path` (a versioned binary file, written whole or
  /// not at all): everything a later step reads, so that restore() continues bit for bit.
  void save_checkpoint(const std::string& path) const;
  /// Replaces the current state by the checkpoint at `path`, written by a run of this same scene
  /// (only settings.duration, output and threads may differ). Throws InputError naming the file
  /// and what differs, leaving the state as it was. The next run() continues the checkpoint's
  /// output directory (its frames, probes.csv and .pvd up to the checkpoint) when it writes there.
  void restore(const std::string& path);

  /// Probe columns (after time) and their values at the current state, in the order of
  /// probes.csv.
  std::vector<std::string> probe_names() const;
  std::vector<double> probe_values() const;

  /// Seconds spent in each stage of the steps taken so far (the stage names of run.json).
  std::map<std::string, double> stage_times() const;

 private:
  friend class SceneBuilder;  // scene_builder.hpp: a scene built in code
  explicit World(std::unique_ptr<Scene> scene);
  std::unique_ptr<Scene> scene_;
  std::unique_ptr<Engine> engine_;  // steps scene_'s state
  long steps_ = 0;
  std::unique_ptr<CheckpointHeader> identity_;  // the scene as checkpoints identify it (at its start)
  std::unique_ptr<RestartPoint> restart_;       // the restored checkpoint, until the next run
};

}  // namespace moreau
