#pragma once
// An engine as the one run loop (run_loop.cpp) sees it: a state it advances by a step function,
// and the fields it exposes (probe columns and values, frames, its part of run.json). The loop
// writes probes.csv, frames, run.json, the progress bar and the timings once for every engine.
// Engines: the constraint engine (a registered Solver over the Model; constraint_engine.cpp),
// FEM solids with rigid bodies and joints (solid_engine.cpp) and the Navier-Stokes flow
// (flow_engine.cpp); engine_list.cpp picks one for a scene.
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "moreau/io/pvd_collection.hpp"
#include "moreau/math/types.hpp"
#include "moreau/world.hpp"

namespace moreau {

struct Scene;
class ArchiveWriter;
class ArchiveReader;

class Engine {
 public:
  virtual ~Engine() = default;

  /// Simulated time of the current state, s.
  virtual double time() const = 0;
  /// The length of one step, s; 0 for an engine that solves once (a steady flow): the run is then
  /// that one solve, and only its result is sampled.
  virtual double dt() const = 0;
  /// The scene's settings.threads: the most threads a step may use (0 = all cores).
  virtual int requested_threads() const = 0;

  /// Advances the current state by one step on `threads` threads (results do not depend on the
  /// count). Throws NumericalError naming the step, the time and the object when the step fails;
  /// the state is then what the failed step left (the constraint engine's diverged values, the
  /// solver's last iterate), not a state to continue from.
  virtual void step(int threads) = 0;

  /// probes.csv's columns (after "time"), and the probes' values at the current state in that order.
  virtual std::vector<std::string> probe_columns() const = 0;
  virtual void sample_probes(std::vector<Real>& values) const = 0;

  /// Starts the frames of a run in `out_dir` (frames/, <scene>.pvd), or continues `resume` (a
  /// restarted run), then writes one per call.
  virtual void open_frames(const std::string& out_dir, const std::string& scene_name, FrameSeries resume) = 0;
  virtual void write_frame() = 0;
  /// The frames written since open_frames (none before it).
  virtual FrameSeries frame_series() const = 0;
  /// Output that describes the final state only (a flow's line probes); written when the run ends.
  virtual void write_final_output(const std::string& /*out_dir*/) const {}

  /// The engine's fields of run.json: counts, solver statistics and stage timings, and (when the
  /// run completed) the final energies.
  virtual void add_run_fields(nlohmann::json& run, bool completed) const = 0;
  /// What the user should know after a run (printed to stderr as "warning: ...").
  virtual std::vector<std::string> warnings() const { return {}; }

  /// A human-readable account of what the scene builds (`moreau check`).
  virtual std::string summary() const = 0;

  /// Checkpoints (run/checkpoint.hpp): everything a later step reads — the state, warm starts,
  /// the time scheme's history, lagged preconditioners — and the counters that probes and run.json
  /// report, so that a restored engine continues bit for bit. load_state reads what save_state of
  /// the same scene wrote (the checkpoint's header has checked that) and throws ArchiveError if
  /// the data do not fit.
  virtual void save_state(ArchiveWriter& out) const = 0;
  virtual void load_state(ArchiveReader& in) = 0;

  /// The name World::engine reports ("xpbd", "fem", "flow").
  virtual std::string name() const = 0;
  /// The scene's objects and where their items sit in the state arrays.
  virtual std::vector<WorldObject> objects() const = 0;
  /// Views of the current state (World::arrays lists them by engine).
  virtual std::vector<StateArray> state_arrays() = 0;
  /// Seconds spent in each stage of the steps so far.
  virtual std::map<std::string, double> stage_times() const = 0;
};

/// The engine of a loaded scene, stepping the scene's own model and state (the scene must outlive
/// it and stay where it is).
std::unique_ptr<Engine> make_engine(Scene& scene);

}  // namespace moreau
