// The run loop of a FEM scene with a "fluid": a steady solve (with viscosity continuation) or
// time steps of the chosen integrator, writing probes.csv, line_<name>.csv, frames with velocity,
// pressure and vorticity, and run.json.
#include <filesystem>
#include <fmt/format.h>
#include <omp.h>

#include <chrono>
#include <fstream>
#include <nlohmann/json.hpp>

#include "moreau/solvers/thread_budget.hpp"
#include "moreau/io/output_budget.hpp"
#include "moreau/fem/scene/fem_output.hpp"
#include "moreau/fem/flow/flow_stepper.hpp"
#include "moreau/run/fem_run.hpp"
#include "moreau/io/frame_writer.hpp"
#include "moreau/io/probe_csv.hpp"
#include "moreau/io/progress_bar.hpp"
#include "moreau/io/run_summary.hpp"

namespace moreau {

namespace {

const char* flow_integrator_name(FlowIntegrator i) {
  switch (i) {
    case FlowIntegrator::steady: return "steady";
    case FlowIntegrator::backward_euler: return "backward_euler";
    case FlowIntegrator::bdf2: return "bdf2";
    case FlowIntegrator::midpoint: return "midpoint";
  }
  return "";
}

// One .vtu per output step: velocity, pressure and vorticity at the nodes (2D in the xy plane).
class FlowFrameWriter {
 public:
  FlowFrameWriter(const FlowProblem& problem, std::string out_dir, std::string scene_name)
      : model_(problem.model), out_dir_(std::move(out_dir)), scene_name_(std::move(scene_name)) {}

  void write(const VectorX& x, Real time) {
    const Index n = model_.mesh.node_count();
    std::vector<Vec3> velocity(n, Vec3::Zero());
    std::vector<Real> pressure(n);
    for (Index a = 0; a < n; ++a) {
      for (int k = 0; k < model_.dim(); ++k) velocity[a][k] = x[model_.dof(a, k)];
      pressure[a] = x[model_.dof(a, model_.dim())];
    }
    std::vector<VtkPointArray> vectors{{"velocity", velocity}};
    std::vector<VtkScalarArray> scalars{{"pressure", pressure}};
    const std::vector<Vec3> curl = nodal_vorticity(model_, x);
    if (model_.dim() == 2) {
      std::vector<Real> w(n);
      for (Index a = 0; a < n; ++a) w[a] = curl[a].z();
      scalars.push_back({"vorticity", w});
    } else {
      vectors.push_back({"vorticity", curl});
    }
    const std::string file = fmt::format("frames/fluid_{:06d}.vtu", frame_++);
    write_vtu(out_dir_ + "/" + file, model_.mesh.nodes, model_.mesh.cells, model_.mesh.nodes_per_cell(),
              vtk_cell(model_.mesh.element), vectors, {}, scalars);
    entries_.push_back({time, 0, file});
    write_pvd(out_dir_ + "/" + scene_name_ + ".pvd", entries_);
  }

 private:
  const NavierStokesModel& model_;
  std::string out_dir_, scene_name_;
  std::vector<PvdEntry> entries_;
  int frame_ = 0;
};

// "pressure_reference": {"mean": value}: shift the pressure so that its mean is the value.
void shift_to_mean_pressure(const FlowProblem& problem, VectorX& x) {
  if (!problem.mean_pressure) return;
  const NavierStokesModel& m = problem.model;
  const Real shift = *problem.mean_pressure - mean_pressure(m, x);
  for (Index n = 0; n < m.mesh.node_count(); ++n) x[m.dof(n, m.dim())] += shift;
}

}  // namespace

std::string flow_summary(const Scene& scene) {
  const FlowProblem& p = *scene.fem->flow;
  const NavierStokesModel& m = p.model;
  std::string s = fmt::format("scene '{}' ({}): solver fem ({}D fluid), integrator {}", scene.name, scene.file, m.dim(),
                              flow_integrator_name(p.integrator));
  if (p.integrator != FlowIntegrator::steady)
    s += fmt::format(", dt {} s, duration {} s", scene.fem->dt, scene.duration);
  s += fmt::format("\n  fluid: {} nodes, {} {} cells, density {} kg/m^3, viscosity {} Pa s\n", m.mesh.node_count(),
                   m.mesh.cell_count(), element_name(m.mesh.element), m.density, m.viscosity);
  s += fmt::format("  unknowns {} ({} free), Jacobian nonzeros {}, probes {}\n", m.dof_count(), m.free_count,
                   m.pattern.nonZeros(), p.probes.size());
  return s;
}

RunResult run_flow_scene(Scene& scene, const RunOptions& options) {
  FlowProblem& problem = *scene.fem->flow;
  NavierStokesModel& model = problem.model;
  if (options.threads) model.threads = *options.threads;
  const int threads = model.threads > 0 ? model.threads : omp_get_max_threads();
  const bool steady = problem.integrator == FlowIntegrator::steady;
  const Real dt = steady ? 0 : scene.fem->dt;
  const double duration = options.duration.value_or(scene.duration);

  const long steps = steady ? 1 : run_step_count(duration, dt);
  const auto started = std::filesystem::file_time_type::clock::now();
  RunResult result;
  result.out_dir = run_output_directory(options.out_dir, scene.name);
  FlowFrameWriter frames(problem, result.out_dir, scene.name);
  ProbeCsv csv(result.out_dir, probe_table_columns(problem.probes, [&](const FlowProbe& p) {
                 return flow_probe_columns(p, model.dim());
               }));

  VectorX x = problem.initial;
  Real time = 0;
  int last_iterations = 0;
  long total_iterations = 0, picard_iterations = 0;
  int max_iterations = 0;
  double assembly_s = 0, solve_s = 0, wall = 0;
  FlowStepper stepper(problem.integrator);
  const FlowTimeStep steady_step;
  const FlowTimeStep* step = &steady_step;  // the last step's scheme, for the reactions of boundary_force
  std::vector<Real> values;
  auto sample = [&] {
    values.clear();
    for (const FlowProbe& p : problem.probes) evaluate_flow_probe(p, problem, x, *step, last_iterations, values);
    csv.write_row(time, values);
    if (scene.output.write_vtk) frames.write(x, time);
  };
  auto account = [&](const FlowSolveResult& r) {
    assembly_s += r.assembly_s;
    solve_s += r.solve_s;
    last_iterations = r.iterations + r.picard_iterations;
    total_iterations += r.iterations;
    picard_iterations += r.picard_iterations;
    max_iterations = std::max(max_iterations, last_iterations);
  };

  FlowLinearSolver solver(problem.linear);
  std::string status = "completed", message;
  nlohmann::json stages = nlohmann::json::array();
  if (steady) {
    // Continuation: each viscosity's solution starts the next; the model's own comes last.
    const Real target = model.viscosity;
    std::vector<Real> viscosities = problem.continuation;
    viscosities.push_back(target);
    for (size_t stage = 0; stage < viscosities.size(); ++stage) {
      const Real mu = viscosities[stage];
      model.viscosity = mu;
      FlowSolveSettings settings = problem.solve;
      if (stage + 1 < viscosities.size()) settings.tolerance = std::max(settings.tolerance, problem.continuation_tolerance);
      const auto t0 = std::chrono::steady_clock::now();
      const FlowSolveResult r = stepper.step(model, 0, 0, x, solver, settings);
      wall += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      account(r);
      stages.push_back({{"viscosity", mu}, {"newton_iterations", r.iterations}, {"picard_iterations", r.picard_iterations}});
      if (!r.converged) {
        status = "failed";
        message = fmt::format("the steady solve of the fluid at viscosity {} Pa s failed: {}", mu, r.failure);
        break;
      }
    }
    model.viscosity = target;
    if (status == "completed") {
      shift_to_mean_pressure(problem, x);
      result.steps = 1;
      sample();
    }
  } else {
    ProgressBar progress(options.progress, duration);
    sample();
    csv.flush();
    check_output_budget(result.out_dir, steps, scene.output.every, started);
    // The requested thread count is a maximum: cores that other processes keep busy are left to them.
    ThreadBudget budget(model.threads);
    const int requested_threads = model.threads;
    for (long s = 0; s < steps; ++s) {
      model.threads = budget.next_step_threads();
      const VectorX start = x;
      const auto t0 = std::chrono::steady_clock::now();
      FlowSolveResult r;
      try {  // a boundary value that is not finite throws NumericalError naming itself and t
        r = stepper.step(model, time, dt, x, solver, problem.solve);
      } catch (const NumericalError& e) {
        r.converged = false;
        r.failure = e.what();
      }
      step = &stepper.last_step();
      wall += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      if (!r.converged || !x.allFinite()) {
        status = "failed";
        message = fmt::format("step {} (t = {:.6g} s to {:.6g} s) failed: fluid: {}", s + 1, time, time + dt,
                              r.converged ? "the velocity or pressure is not finite" : r.failure);
        x = start;
        break;
      }
      account(r);
      shift_to_mean_pressure(problem, x);
      time += dt;
      result.steps = s + 1;
      if ((s + 1) % scene.output.every == 0 || s + 1 == steps) sample();
      progress.update(time, result.steps, wall);
    }
    progress.finish();
    model.threads = requested_threads;
  }
  for (const FlowProbe& p : problem.probes)
    if (p.type == FlowProbeType::line) write_line_probe(p, problem, x, result.out_dir + "/line_" + safe_file_name(p.name) + ".csv");
  result.wall_time_s = wall;

  nlohmann::json j = run_summary_json({scene.name, scene.file, "fem", status, message, dt, time, wall, threads, result.steps});
  j["integrator"] = flow_integrator_name(problem.integrator);
  j["counts"] = {{"fluid_nodes", model.mesh.node_count()}, {"cells", model.mesh.cell_count()},
                 {"unknowns", model.dof_count()}, {"free_unknowns", model.free_count}};
  j["newton"] = {{"iterations", total_iterations},    {"picard_iterations", picard_iterations},
                 {"max_iterations_per_step", max_iterations}, {"tolerance", problem.solve.tolerance},
                 {"assembly_s", assembly_s},           {"solve_s", solve_s}};
  j["linear_solver"] = {{"type", solver.name()}};
  if (problem.linear.method == FlowLinearMethod::gmres) {
    const FlowLinearStatistics& ls = solver.statistics();
    j["linear_solver"].update(nlohmann::json{{"solves", ls.solves},
                                             {"retries", ls.retries},
                                             {"gmres_iterations", ls.iterations},
                                             {"max_gmres_iterations_per_solve", ls.max_iterations},
                                             {"preconditioner_updates", ls.preconditioner_updates},
                                             {"preconditioner_s", ls.preconditioner_s},
                                             {"tolerance", problem.linear.tolerance}});
  }
  if (steady) j["continuation"] = stages;
  std::ofstream(result.out_dir + "/run.json") << j.dump(2) << '\n';
  if (status != "completed") throw NumericalError(message);
  return result;
}

}  // namespace moreau
