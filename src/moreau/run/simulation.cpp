// The run loop behind moreau::Simulation: step, sample probes, write frames, time the stages,
// draw progress, and write run.json.
#include <algorithm>
#include <fmt/format.h>
#include <omp.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "moreau/io/output_budget.hpp"
#include "moreau/scene/memory_estimate.hpp"
#include "moreau/io/frame_writer.hpp"
#include "moreau/io/probe_csv.hpp"
#include "moreau/io/progress_bar.hpp"
#include "moreau/io/run_summary.hpp"
#include "moreau/model/diagnostics.hpp"
#include "moreau/moreau.hpp"
#include "moreau/scene/scene.hpp"
#include "moreau/solvers/thread_budget.hpp"
#include "moreau/solvers/xpbd/xpbd_stages.hpp"
#include "moreau/solvers/xpbd/xpbd_step.hpp"
#include "moreau/run/fem_run.hpp"

namespace moreau {

namespace fs = std::filesystem;

const char* version() { return MOREAU_VERSION; }

void set_memory_limit(double bytes) { set_memory_limit_bytes(bytes); }

Simulation::Simulation(std::unique_ptr<Scene> scene) : scene_(std::move(scene)) {}
Simulation::~Simulation() = default;
Simulation::Simulation(Simulation&&) noexcept = default;
Simulation& Simulation::operator=(Simulation&&) noexcept = default;

Simulation Simulation::load(const std::string& scene_path, const std::vector<std::string>& overrides) {
  return Simulation(std::make_unique<Scene>(load_scene(scene_path, overrides)));
}

const std::string& Simulation::name() const { return scene_->name; }
Scene& Simulation::internals() { return *scene_; }
double Simulation::time() const { return scene_->state.time; }

void Simulation::step() {
  if (scene_->fem) throw InputError("Simulation::step is not available for \"solver\": \"fem\" scenes; use run");
  StageTimer timer;
  scene_->formulation->step(scene_->model, scene_->state, timer, solver_thread_count(scene_->model));
}

std::vector<double> Simulation::position(const std::string& object, int vertex) const {
  const Index o = scene_->model.find_object(object);
  if (o < 0 || vertex < 0 || vertex >= scene_->model.objects[o].particle_count())
    throw InputError(fmt::format("no vertex {} in object '{}'", vertex, object));
  const Vec3& x = scene_->state.position[scene_->model.objects[o].particle_begin + vertex];
  return {x.x(), x.y(), x.z()};
}

std::string Simulation::summary() const {
  if (scene_->fem) return fem_summary(*scene_);
  const Model& m = scene_->model;
  std::string s = fmt::format("scene '{}' ({}): solver {}, dt {} s, {} substeps x {} iterations, duration {} s\n",
                              scene_->name, scene_->file, scene_->solver, m.settings.dt, m.settings.substeps,
                              m.settings.iterations, scene_->duration);
  for (const auto& o : m.objects) {
    static const char* kinds[] = {"collider", "cloth", "soft_body", "fluid", "rigid_body"};
    s += fmt::format("  {:<10} {:<16}", kinds[static_cast<int>(o.kind)], o.name);
    if (o.kind == ObjectKind::fluid) {
      Index count = 0;
      for (Index p : m.fluid.initial_phase) count += p == o.fluid_phase;
      s += fmt::format(" {} particles of radius {} m, rest density {} kg/m^3", count, m.fluid.particle_radius,
                       m.fluid.phases[o.fluid_phase].rest_density);
    }
    if (o.kind == ObjectKind::rigid_body) {
      static const char* shapes[] = {"sphere", "box", "capsule", "cylinder", "convex hull", "plane"};
      static const char* motions[] = {"dynamic", "fixed", "kinematic"};
      const RigidBodyModel& r = m.rigid;
      s += fmt::format(" {} {}, mass {:.6g} kg, principal inertia ({:.4g}, {:.4g}, {:.4g}) kg m^2",
                       motions[static_cast<int>(r.body_motion[o.body])], shapes[static_cast<int>(r.body_shape[o.body].type)],
                       r.body_mass[o.body], r.body_inertia[o.body].x(), r.body_inertia[o.body].y(),
                       r.body_inertia[o.body].z());
    }
    if (o.has_particles())
      s += fmt::format(" {} particles, {} surface triangles, {} tetrahedra", o.particle_count(), o.surface.size(), o.tets.size());
    s += "\n";
  }
  for_each_family(m.constraints, [&](const auto& family, int) {
    if (family.size() == 0) return;
    s += fmt::format("  constraints {:<17} {:>8}  in {} colours\n", family.kName, family.size(),
                     family.batches.color_count());
  });
  if (!m.joints.empty()) s += fmt::format("  joints: {}\n", m.joints.size());
  if (!m.fluid.empty())
    s += fmt::format("  fluid: support h = {} m, {} collider wall samples\n", m.fluid.support(), m.fluid.boundary.size());
  s += fmt::format("  probes: {}\n", scene_->probes.size());
  return s;
}

namespace {

nlohmann::json xpbd_run_summary_json(const Scene& scene, const StageTimer& timer, const State& state, long steps,
                                double wall_time, int threads, const std::string& status, const std::string& message) {
  const Model& m = scene.model;
  nlohmann::json j = run_summary_json(
      {scene.name, scene.file, scene.solver, status, message, m.settings.dt, state.time, wall_time, threads, steps});
  j["substeps"] = m.settings.substeps;
  j["iterations"] = m.settings.iterations;
  nlohmann::json constraints = nlohmann::json::object();
  for_each_family(m.constraints, [&](const auto& family, int) { constraints[std::string(family.kName)] = family.size(); });
  j["counts"] = {{"particles", m.particle_count()},
                 {"fluid_particles", state.fluid.count},
                 {"objects", m.objects.size()},
                 {"colliders", m.colliders.size()},
                 {"rigid_bodies", std::count_if(m.objects.begin(), m.objects.end(),
                                                [](const ObjectInfo& o) { return o.kind == ObjectKind::rigid_body; })},
                 {"joints", m.joints.size()},
                 {"constraints", constraints}};
  nlohmann::json stages = nlohmann::json::object();
  const std::vector<std::string> names = scene.formulation->stage_names();
  for (int s = 0; s < static_cast<int>(names.size()); ++s) stages[names[s]] = timer.seconds(s);
  j["stage_time_s"] = stages;
  if (!m.fluid.empty())
    j["fluid"] = {{"neighbor_list_builds", state.fluid.list_builds},
                  {"max_cfl_number", state.fluid.max_cfl},
                  {"cfl_limit", m.fluid.cfl_limit},
                  {"steps_over_cfl_limit", state.fluid.cfl_violations},
                  {"wall_samples", m.fluid.boundary.size()}};
  if (status == "completed") {
    j["final_energy_j"] = {{"kinetic", kinetic_energy(m, state, -1)},
                           {"potential", potential_energy(m, state, -1)},
                           {"elastic", elastic_energy(m, state, -1)}};
  }
  return j;
}

}  // namespace

RunResult Simulation::run(const RunOptions& options) {
  Scene& scene = *scene_;
  if (scene.fem) return run_fem_scene(scene, options);
  const Model& model = scene.model;
  Solver& solver = *scene.formulation;
  const int requested_threads = options.threads.value_or(model.settings.threads);
  const double duration = options.duration.value_or(scene.duration);
  const int threads = requested_threads > 0 ? requested_threads : omp_get_max_threads();

  const long steps = run_step_count(duration, model.settings.dt);
  const auto started = std::filesystem::file_time_type::clock::now();
  RunResult result;
  result.out_dir = run_output_directory(options.out_dir, scene.name);
  const fs::path dir(result.out_dir);

  State& state = scene.state;
  FrameWriter frames(model, result.out_dir, scene.name);
  ProbeCsv csv(result.out_dir, probe_table_columns(scene.probes, [](const auto& p) { return probe_columns(p); }));
  std::vector<Real> values;
  auto sample = [&] {
    values.clear();
    for (const auto& p : scene.probes) evaluate_probe(p, model, state, values);
    csv.write_row(state.time, values);
    if (scene.output.write_vtk) frames.write(state);
  };

  StageTimer timer;
  ProgressBar progress(options.progress, duration);
  sample();
  csv.flush();
  check_output_budget(result.out_dir, steps, scene.output.every, started);
  double wall = 0;
  std::string status = "completed", message;
  // The requested thread count is a maximum: cores that other processes keep busy are left to them.
  ThreadBudget budget(requested_threads);
  try {
    for (long s = 0; s < steps; ++s) {
      const int step_threads = budget.next_step_threads();
      const auto t0 = std::chrono::steady_clock::now();
      solver.step(model, state, timer, step_threads);
      wall += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      result.steps = s + 1;
      if ((s + 1) % scene.output.every == 0 || s + 1 == steps) sample();
      progress.update(state.time, result.steps, wall);
    }
  } catch (const NumericalError& e) {
    status = "failed";
    message = e.what();
  }
  progress.finish();
  if (state.fluid.cfl_violations > 0)
    fmt::print(stderr,
               "warning: the fluid CFL number max|v| h / (2 r) reached {:.2f} (limit {}) in {} steps; the time step is "
               "too long for the fastest particles: lower settings.dt or raise settings.substeps\n",
               state.fluid.max_cfl, model.fluid.cfl_limit, state.fluid.cfl_violations);
  result.wall_time_s = wall;
  std::ofstream(dir / "run.json") << xpbd_run_summary_json(scene, timer, state, result.steps, wall, threads, status, message).dump(2)
                                  << '\n';
  if (status != "completed") throw NumericalError(message);
  return result;
}

}  // namespace moreau
