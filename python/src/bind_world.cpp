// moreau.World: a scene loaded from a file or a dict, stepped without the GIL, its state as numpy
// views into the engine's storage, its probes as arrays.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "moreau/io/output_budget.hpp"
#include "moreau/world.hpp"
#include "python_bindings.hpp"
#include "sigint_forwarding.hpp"

namespace py = pybind11;

namespace moreau::python {
namespace {

// A World owned by Python. Steps run with the GIL released, so the mutex keeps two Python threads
// from stepping (or reading probes of) the same World at once.
struct WorldHandle {
  explicit WorldHandle(World w) : world(std::move(w)) {}
  World world;
  std::mutex busy;
};

// The state array `a` as a (count, components) numpy array over the engine's own storage: no copy.
// `owner` (the Python World) stays alive while the array does. The storage never moves during the
// World's life (restore() refills it in place), but `count` is the number of items when the view
// was taken: a fluid with emitters has more live particles later, so take the view again.
py::array state_view(const StateArray& a, py::handle owner) {
  const std::vector<py::ssize_t> shape{static_cast<py::ssize_t>(a.count), a.components};
  if (a.count == 0) return py::array_t<double>(shape);
  const std::vector<py::ssize_t> strides{static_cast<py::ssize_t>(a.components * sizeof(double)), sizeof(double)};
  py::array_t<double> view(shape, strides, a.values.data(), owner);
  if (!a.writable) view.attr("setflags")(py::arg("write") = false);
  return view;
}

// Steps `count` times, each without the GIL; Python's signal handlers (Ctrl-C) run between steps.
void step_times(WorldHandle& h, long count, std::optional<int> threads) {
  for (long s = 0; s < count; ++s) {
    {
      py::gil_scoped_release unlocked;
      std::lock_guard<std::mutex> lock(h.busy);
      threads ? h.world.step(*threads) : h.world.step();
    }
    if (PyErr_CheckSignals() != 0) throw py::error_already_set();
  }
}

std::vector<std::string> with_solver(std::vector<std::string> overrides, const std::optional<std::string>& solver) {
  if (solver) overrides.push_back("settings.solver=" + *solver);
  return overrides;
}

constexpr const char* kWorldDoc = R"(A scene and the engine that steps it.

Load one with World.load(path) or World.from_dict(scene) (moreau.World.from_json for text). Step it
with step(), run it to an output directory with run(), read and write its state between steps as
numpy arrays with array(name) and arrays(), and read its probes with probes() or record().

Units are SI throughout. A step releases the GIL; results do not depend on the thread count.)";

constexpr const char* kArrayDoc = R"(One array of the current state as a (count, components) numpy array.

The array is a view into the engine's storage (no copy): it follows the state as the World steps,
and writing a writable array (e.g. particle.velocity) changes the state the next step starts
from. Read-only arrays (fluid.position, fluid.density, fluid.pressure, fluid.enthalpy) raise on writing. The view
keeps the World alive. Its length is the item count when it was taken: a fluid with emitters has
more live particles later, so take it again after steps. array_units() gives each array's unit.

Names by engine:
  constraint engine  particle.position (m), particle.velocity (m/s), particle.angular_velocity
                     (rad/s); body.position (m), body.orientation (unit quaternion x y z w),
                     body.velocity (m/s), body.angular_velocity (rad/s, world frame);
                     fluid.position (m), fluid.velocity (m/s), fluid.density (kg/m^3),
                     fluid.pressure (Pa), fluid.enthalpy (J/kg), fluid.smoke (a gas's smoke
                     concentration), in the order of a space-filling curve
  fem                solid.displacement (m), solid.velocity (m/s); body.director_state (24 values:
                     x, d1, d2, d3, v, v_d1, v_d2, v_d3)
  flow               flow.solution: the velocity (m/s) then the pressure (Pa) per node
Raises InputError naming the arrays there are.)";

}  // namespace

void bind_world(py::module_& m) {
  py::class_<WorldObject>(m, "WorldObject", "What a scene object became: its kind and where its items sit in the arrays.")
      .def_readonly("name", &WorldObject::name)
      .def_readonly("kind", &WorldObject::kind, "'cloth', 'soft_body', 'rigid_body', 'fluid', 'collider', 'solid', ...")
      .def_readonly("first", &WorldObject::first, "index of its first item in its kind's arrays (particles or bodies)")
      .def_readonly("count", &WorldObject::count, "number of items (particles, bodies, or fluid particles of its phase)")
      .def("__repr__", [](const WorldObject& o) {
        return "WorldObject(name='" + o.name + "', kind='" + o.kind + "', first=" + std::to_string(o.first) +
               ", count=" + std::to_string(o.count) + ")";
      });

  py::class_<RunResult>(m, "RunResult", "What World.run did.")
      .def_readonly("steps", &RunResult::steps, "steps this run took")
      .def_readonly("wall_time_s", &RunResult::wall_time_s, "seconds spent stepping")
      .def_readonly("out_dir", &RunResult::out_dir, "the output directory written")
      .def_readonly("checkpoint", &RunResult::checkpoint, "the last checkpoint written ('' if none)")
      .def("__repr__", [](const RunResult& r) {
        return "RunResult(steps=" + std::to_string(r.steps) + ", wall_time_s=" + std::to_string(r.wall_time_s) +
               ", out_dir='" + r.out_dir + "', checkpoint='" + r.checkpoint + "')";
      });

  py::class_<WorldHandle>(m, "World", kWorldDoc)
      .def_static(
          "load",
          [](const std::string& path, std::vector<std::string> overrides, std::optional<std::string> solver) {
            return std::make_unique<WorldHandle>(World::load(path, with_solver(std::move(overrides), solver)));
          },
          py::arg("path"), py::arg("overrides") = std::vector<std::string>{}, py::arg("solver") = py::none(),
          "Loads and validates a scene file. overrides are 'json.path=value' assignments, as the command\n"
          "line's --set; solver (e.g. 'xpbd', 'nmd', 'xpbi') sets settings.solver. Raises InputError\n"
          "naming the file, the JSON path and what is allowed.")
      .def_static(
          "from_json",
          [](const std::string& text, std::vector<std::string> overrides, std::optional<std::string> solver) {
            return std::make_unique<WorldHandle>(World::from_json(text, with_solver(std::move(overrides), solver)));
          },
          py::arg("text"), py::arg("overrides") = std::vector<std::string>{}, py::arg("solver") = py::none(),
          "The same for scene JSON text; relative mesh paths are resolved against the working directory.")
      .def_property_readonly("name", [](WorldHandle& h) { return h.world.name(); })
      .def_property_readonly("engine", [](WorldHandle& h) { return h.world.engine(); },
                             "the engine that steps the scene: the constraint solver's name ('xpbd', ...), 'fem' or 'flow'")
      .def_property_readonly("time", [](WorldHandle& h) { return h.world.time(); }, "simulated time, s")
      .def_property_readonly("dt", [](WorldHandle& h) { return h.world.dt(); }, "one step, s (0 for a steady flow)")
      .def_property_readonly("steps", [](WorldHandle& h) { return h.world.steps(); },
                             "steps from the scene's start (those of a restored checkpoint included)")
      .def("summary", [](WorldHandle& h) { return h.world.summary(); }, "What the scene builds, in words.")
      .def("objects", [](WorldHandle& h) { return h.world.objects(); }, "The scene's objects (WorldObject), in scene order.")
      .def("step", &step_times, py::arg("count") = 1, py::arg("threads") = py::none(),
           "Advances `count` steps of dt on settings.threads threads (or `threads`), without the GIL.\n"
           "Raises NumericalError naming the step, the time and the object.")
      .def(
          "run",
          [](WorldHandle& h, std::optional<std::string> out_dir, std::optional<double> duration,
             std::optional<int> threads, std::optional<int> checkpoint_every, bool progress) {
            RunOptions options;
            options.out_dir = out_dir.value_or("");
            options.duration = duration;
            options.threads = threads;
            options.checkpoint_every = checkpoint_every;
            options.progress = progress;
            RunResult result;
            {
              const SigintForwarding forwarding;  // Ctrl-C stops the run after its step, with a checkpoint
              py::gil_scoped_release unlocked;
              std::lock_guard<std::mutex> lock(h.busy);
              result = h.world.run(options);
            }
            if (result.stopped_by_signal != 0) {
              PyErr_SetString(PyExc_KeyboardInterrupt,
                              ("the run stopped after step " + std::to_string(h.world.steps()) + "; checkpoint: " +
                               result.checkpoint + " (World.restore continues it)")
                                  .c_str());
              throw py::error_already_set();
            }
            return result;
          },
          py::arg("out_dir") = py::none(), py::arg("duration") = py::none(), py::arg("threads") = py::none(),
          py::arg("checkpoint_every") = py::none(), py::arg("progress") = false,
          "Runs from the current state for the scene's duration (or `duration`, s) and writes the output\n"
          "directory (default out/<scene name>): run.json, probes.csv, <scene>.pvd and frames/, exactly\n"
          "as `moreau run`. checkpoint_every writes checkpoint.bin every that many steps. Ctrl-C stops\n"
          "the run after its step, writes a checkpoint and raises KeyboardInterrupt naming it.\n"
          "Raises NumericalError if a step fails (the output so far and run.json remain).")
      .def(
          "array",
          [](py::object self, const std::string& name) { return state_view(self.cast<WorldHandle&>().world.array(name), self); },
          py::arg("name"), kArrayDoc)
      .def(
          "arrays",
          [](py::object self) {
            py::dict all;
            for (const StateArray& a : self.cast<WorldHandle&>().world.arrays()) all[py::str(a.name)] = state_view(a, self);
            return all;
          },
          "Every array of the current state, by name (see array()).")
      .def(
          "array_units",
          [](WorldHandle& h) {
            py::dict units;
            for (const StateArray& a : h.world.arrays()) units[py::str(a.name)] = a.unit;
            return units;
          },
          "The SI unit of each state array, by name ('' for dimensionless).")
      .def_property_readonly("probe_names", [](WorldHandle& h) { return h.world.probe_names(); },
                             "the probe columns of probes.csv (after time)")
      .def(
          "probes",
          [](WorldHandle& h) {
            std::lock_guard<std::mutex> lock(h.busy);
            const std::vector<std::string> names = h.world.probe_names();
            const std::vector<double> values = h.world.probe_values();
            py::dict probes;
            for (std::size_t i = 0; i < names.size(); ++i) probes[py::str(names[i])] = values[i];
            return probes;
          },
          "The probes at the current state, by column name (units as in probes.csv).")
      .def(
          "record",
          [](WorldHandle& h, double duration, std::optional<int> threads) {
            const long steps = run_step_count(duration, h.world.dt());
            const std::vector<std::string> names = h.world.probe_names();
            std::vector<py::array_t<double>> columns;  // time, then one per probe
            for (std::size_t i = 0; i <= names.size(); ++i) columns.emplace_back(steps);
            for (long s = 0; s < steps; ++s) {
              step_times(h, 1, threads);
              columns[0].mutable_at(s) = h.world.time();
              const std::vector<double> values = h.world.probe_values();
              for (std::size_t i = 0; i < values.size(); ++i) columns[i + 1].mutable_at(s) = values[i];
            }
            py::dict series;
            series["time"] = columns[0];
            for (std::size_t i = 0; i < names.size(); ++i) series[py::str(names[i])] = columns[i + 1];
            return series;
          },
          py::arg("duration"), py::arg("threads") = py::none(),
          "Steps for `duration` seconds (the steps `run` would take) and returns the probes after every\n"
          "step as numpy arrays by column name, with 'time' (s). Writes nothing.")
      .def(
          "save_checkpoint",
          [](WorldHandle& h, const std::string& path) {
            py::gil_scoped_release unlocked;
            std::lock_guard<std::mutex> lock(h.busy);
            h.world.save_checkpoint(path);
          },
          py::arg("path"),
          "Writes the whole state to `path` (a versioned binary file, written whole or not at all).")
      .def(
          "restore",
          [](WorldHandle& h, const std::string& path) {
            py::gil_scoped_release unlocked;
            std::lock_guard<std::mutex> lock(h.busy);
            h.world.restore(path);
          },
          py::arg("path"),
          "Replaces the state by a checkpoint of this same scene, bit for bit (array views stay valid).\n"
          "Raises InputError naming the file and what differs, leaving the state as it was.")
      .def("stage_times", [](WorldHandle& h) { return h.world.stage_times(); },
           "Seconds spent in each stage of the steps so far (the stage names of run.json).")
      .def("__repr__", [](WorldHandle& h) {
        return "World('" + h.world.name() + "', engine='" + h.world.engine() + "', time=" + std::to_string(h.world.time()) +
               " s, steps=" + std::to_string(h.world.steps()) + ")";
      });
}

}  // namespace moreau::python
