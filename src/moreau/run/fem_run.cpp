#include "moreau/solvers/thread_budget.hpp"
#include "moreau/io/output_budget.hpp"
#include "moreau/run/fem_run.hpp"

#include <filesystem>
#include <fmt/format.h>
#include <omp.h>

#include <chrono>
#include <fstream>
#include <nlohmann/json.hpp>

#include "moreau/fem/bodies/coupled_step.hpp"
#include "moreau/fem/solids/fem_assembly.hpp"
#include "moreau/fem/scene/fem_output.hpp"
#include "moreau/io/frame_writer.hpp"
#include "moreau/io/probe_csv.hpp"
#include "moreau/io/progress_bar.hpp"
#include "moreau/io/run_summary.hpp"

namespace moreau {

namespace {

const char* integrator_name(FemIntegrator i) {
  switch (i) {
    case FemIntegrator::static_load_steps: return "static";
    case FemIntegrator::midpoint: return "midpoint";
    case FemIntegrator::energy_momentum: return "energy_momentum";
  }
  return "";
}

}  // namespace

std::string fem_summary(const Scene& scene) {
  if (scene.fem->flow) return flow_summary(scene);
  const FemProblem& p = *scene.fem;
  const FemModel& m = p.model;
  std::string s = fmt::format("scene '{}' ({}): solver fem ({}D), integrator {}, dt {} s, duration {} s\n", scene.name,
                              scene.file, m.dim, integrator_name(p.integrator), p.dt, scene.duration);
  for (const FemSolid& solid : m.solids)
    s += fmt::format("  solid {:<16} {} nodes, {} {} cells, {}, lambda {:.6g} Pa, mu {:.6g} Pa, density {} kg/m^3\n",
                     solid.name, solid.mesh.node_count(), solid.mesh.cell_count(), element_name(solid.mesh.element),
                     solid.material.model == HyperelasticModel::neo_hookean ? "Neo-Hookean" : "St. Venant-Kirchhoff",
                     solid.material.lame.lambda, solid.material.lame.mu, solid.material.density);
  for (const FemRigidBody& b : p.rigid_bodies)
    s += fmt::format("  rigid body {:<11} {} nodes, mass {:.6g} kg, Euler tensor ({:.4g}, {:.4g}, {:.4g}) kg m^2 (director frame)\n",
                     b.name, b.mesh.node_count(), b.body.mass, b.body.euler[0], b.body.euler[1], b.body.euler[2]);
  for (const FemJoint& j : p.joints) s += fmt::format("  joint {:<16} {} constraint rows\n", j.name, j.row_count());
  s += fmt::format("  dofs {} ({} free, {} prescribed), loads {}, tangent nonzeros {}\n", m.dof_count(), m.free_count,
                   m.dof_count() - m.free_count, m.loads.size(), m.pattern.nonZeros());
  s += fmt::format("  probes: {}\n", p.probes.size());
  return s;
}

RunResult run_fem_scene(Scene& scene, const RunOptions& options) {
  if (scene.fem->flow) return run_flow_scene(scene, options);
  FemProblem& problem = *scene.fem;
  FemModel& model = problem.model;
  if (options.threads) model.threads = *options.threads;
  const int threads = model.threads > 0 ? model.threads : omp_get_max_threads();
  const double duration = options.duration.value_or(scene.duration);
  const Real dt = scene.fem->dt;

  const long steps = run_step_count(duration, dt);
  const auto started = std::filesystem::file_time_type::clock::now();
  RunResult result;
  result.out_dir = run_output_directory(options.out_dir, scene.name);
  FemFrameWriter frames(problem, result.out_dir, scene.name);
  ProbeCsv csv(result.out_dir, probe_table_columns(problem.probes, [&](const FemProbe& p) {
                 return fem_probe_columns(p, model.dim);
               }));

  FemRunState run;
  for (const FemRigidBody& b : problem.rigid_bodies) run.bodies.push_back(b.initial);
  FemDynamicState& state = run.solids;
  state = initial_dynamic_state(model);
  for (Index d = 0; d < model.dof_count(); ++d)
    if (model.free_index[d] >= 0) state.v[d] = problem.initial_velocity[d];
  // A static solve starts from the reference configuration; its first load step's predictor
  // carries the prescribed values in (moving only the boundary nodes would invert cells).
  if (problem.integrator == FemIntegrator::static_load_steps) {
    state.u.setZero();
    state.v.setZero();
  }
  {
    VectorX force;
    state.energy = assemble_internal_forces(model, state.u, force, nullptr).energy;
  }
  int last_iterations = 0;
  long total_iterations = 0;
  int max_iterations = 0;
  double assembly_s = 0, solve_s = 0;
  std::vector<Real> values;
  auto sample = [&] {
    values.clear();
    for (const FemProbe& p : problem.probes) evaluate_fem_probe(p, problem, run, last_iterations, values);
    csv.write_row(state.time, values);
    if (scene.output.write_vtk) frames.write(run);
  };

  const SparseMatrix mass = problem.integrator == FemIntegrator::static_load_steps ? SparseMatrix() : assemble_mass_matrix(model);
  SparseSymmetricSolver solver;
  SparseLuSolver coupled;
  ProgressBar progress(options.progress, duration);
  sample();
  csv.flush();
  check_output_budget(result.out_dir, steps, scene.output.every, started);
  double wall = 0;
  std::string status = "completed", message;
  // The requested thread count is a maximum: cores that other processes keep busy are left to them
  // (the coloured assembly gives the same bits for any count).
  ThreadBudget budget(model.threads);
  const int requested_threads = model.threads;
  for (long s = 0; s < steps; ++s) {
    model.threads = budget.next_step_threads();
    const auto t0 = std::chrono::steady_clock::now();
    NewtonResult r;
    // A load or prescribed value that is not finite throws NumericalError naming itself and t.
    try {
      if (problem.integrator == FemIntegrator::static_load_steps) {
        r = solve_static(model, state.time + dt, state.u, solver, problem.newton);
        if (r.converged) {
          state.time += dt;
          state.energy = r.energy;
        }
      } else {
        const StepRule rule = problem.integrator == FemIntegrator::midpoint ? StepRule::midpoint : StepRule::energy_momentum;
        if (!problem.joints.empty()) {
          // Joints couple solids and bodies: one Newton system for everything.
          r = step_coupled(problem, mass, rule, dt, run, coupled, problem.newton);
        } else if (model.dof_count() > 0) {
          r = step_dynamic(model, mass, rule, dt, state, solver, problem.newton);
        } else {
          r.converged = true;
          state.time += dt;
        }
        // Free rigid bodies: the constrained midpoint step (energy and angular momentum conserving
        // for either integrator) under gravity, by the discrete null-space form (six unknowns per
        // body; tested against the multiplier form, which the coupled step with joints uses).
        for (size_t b = 0; b < run.bodies.size() && r.converged && problem.joints.empty(); ++b) {
          const DirectorBody& body = problem.rigid_bodies[b].body;
          const NewtonResult rb =
              step_director_body_reduced(body, dt, body.mass * problem.gravity, Vec3::Zero(), run.bodies[b], problem.newton);
          if (!rb.converged) {
            r.converged = false;
            r.failure = fmt::format("rigid body '{}': {}", problem.rigid_bodies[b].name, rb.failure);
          }
          r.iterations += rb.iterations;
        }
      }
    } catch (const NumericalError& e) {
      r.converged = false;
      r.failure = e.what();
    }
    wall += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (!r.converged) {
      status = "failed";
      message = fmt::format("step {} (t = {:.6g} s to {:.6g} s) failed: {}", s + 1, state.time, state.time + dt, r.failure);
      break;
    }
    assembly_s += r.assembly_s;
    solve_s += r.solve_s;
    last_iterations = r.iterations;
    total_iterations += r.iterations;
    max_iterations = std::max(max_iterations, r.iterations);
    result.steps = s + 1;
    if ((s + 1) % scene.output.every == 0 || s + 1 == steps) sample();
    progress.update(state.time, result.steps, wall);
  }
  progress.finish();
  model.threads = requested_threads;
  result.wall_time_s = wall;

  nlohmann::json j =
      run_summary_json({scene.name, scene.file, "fem", status, message, dt, state.time, wall, threads, result.steps});
  j["integrator"] = integrator_name(problem.integrator);
  Index cells = 0;
  for (const FemSolid& s : model.solids) cells += s.mesh.cell_count();
  j["counts"] = {{"solids", model.solids.size()}, {"rigid_bodies", problem.rigid_bodies.size()}, {"joints", problem.joints.size()}, {"nodes", model.node_count}, {"cells", cells},
                 {"dofs", model.dof_count()},     {"free_dofs", model.free_count}};
  j["newton"] = {{"iterations", total_iterations},
                 {"max_iterations_per_step", max_iterations},
                 {"tolerance", problem.newton.tolerance},
                 {"assembly_s", assembly_s},
                 {"solve_s", solve_s},
                 {"last_linear_solver", problem.joints.empty() ? solver.method() : std::string("umfpack (coupled)")}};
  if (status == "completed")
  {
    Real kinetic = kinetic_energy(model, state.v);
    for (size_t b = 0; b < run.bodies.size(); ++b) kinetic += kinetic_energy(problem.rigid_bodies[b].body, run.bodies[b]);
    j["final_energy_j"] = {{"kinetic", kinetic}, {"strain", state.energy}};
  }
  std::ofstream(result.out_dir + "/run.json") << j.dump(2) << '\n';
  if (status != "completed") throw NumericalError(message);
  return result;
}

}  // namespace moreau
