// The FEM engine for a fluid: the stabilized Navier-Stokes flow, advanced by one step of its
// integrator (FlowStepper) per run-loop step, or solved once when steady (each continuation
// viscosity's solution starting the next, the model's own last). After every solve the pressure is
// shifted to its reference mean, if the scene sets one. Immersed solids (fem/immersed) take part in
// every solve of a transient flow as a momentum source and move with it.
#include "moreau/run/engines.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <limits>
#include <optional>

#include "moreau/errors.hpp"
#include "moreau/fem/flow/flow_frames.hpp"
#include "moreau/fem/flow/flow_stepper.hpp"
#include "moreau/fem/immersed/immersed_coupling.hpp"
#include "moreau/io/binary_archive.hpp"
#include "moreau/io/frame_writer.hpp"
#include "moreau/io/probe_csv.hpp"
#include "moreau/run/state_arrays.hpp"
#include "moreau/scene/scene.hpp"

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

class FlowEngine final : public Engine {
 public:
  explicit FlowEngine(Scene& scene)
      : scene_(scene), problem_(*scene.fem->flow), threads_(scene.fem->threads), x_(problem_.initial),
        stepper_(problem_.integrator), solver_(problem_.linear) {
    if (problem_.immersed) {
      solids_.emplace(initial_immersed_state(*problem_.immersed));
      coupling_.emplace(problem_.model, *problem_.immersed, *solids_);
    }
  }

  double time() const override { return time_; }
  double dt() const override { return steady() ? 0 : scene_.fem->dt; }
  int requested_threads() const override { return threads_; }
  void step(int threads) override { steady() ? solve_steady(threads) : step_transient(threads); }
  std::vector<std::string> warnings() const override {
    if (problem_.linear.options_warning.empty()) return {};
    return {problem_.linear.options_warning};
  }

  std::vector<std::string> probe_columns() const override {
    return probe_table_columns(problem_.probes, [&](const FlowProbe& p) { return flow_probe_columns(p, problem_.model.dim()); });
  }
  void sample_probes(std::vector<Real>& values) const override {
    for (const FlowProbe& p : problem_.probes) evaluate_flow_probe(p, problem_, x_, *last_step_, last_iterations_, immersed_state(), values);
  }
  void open_frames(const std::string& out_dir, const std::string& scene_name, FrameSeries resume) override {
    frames_.emplace(problem_.model, problem_.name, out_dir, scene_name, std::move(resume),
                    problem_.immersed ? &*problem_.immersed : nullptr);
  }
  void write_frame() override { frames_->write(x_, time_, immersed_state()); }
  FrameSeries frame_series() const override { return frames_ ? frames_->series() : FrameSeries{}; }

  void save_state(ArchiveWriter& out) const override {
    archive(out, std::tie(x_, time_, steps_, last_iterations_, max_iterations_, total_iterations_, picard_iterations_,
                          retried_steps_, smallest_step_));
    stepper_.save(out);
    solver_.save(out);
    if (solids_)
      archive(out, std::tie(solids_->displacement, solids_->velocity, solids_->time, solids_->frame, solids_->frame_velocity,
                            solids_->fluid_force, solids_->fluid_torque, solids_->fluid_source));
  }
  void load_state(ArchiveReader& in) override {
    auto fields = std::tie(x_, time_, steps_, last_iterations_, max_iterations_, total_iterations_, picard_iterations_,
                           retried_steps_, smallest_step_);
    unarchive(in, fields);
    if (x_.size() != problem_.initial.size()) throw ArchiveError("the checkpoint's flow has another number of unknowns");
    stepper_.load(in);
    solver_.load(in);
    if (solids_) {
      auto solid_fields = std::tie(solids_->displacement, solids_->velocity, solids_->time, solids_->frame,
                                   solids_->frame_velocity, solids_->fluid_force, solids_->fluid_torque,
                                   solids_->fluid_source);
      unarchive(in, solid_fields);
      if (solids_->displacement.size() != problem_.immersed->model.dof_count())
        throw ArchiveError("the checkpoint's immersed solids have another number of nodes");
      if (solids_->frame.size() != problem_.immersed->rigid_bodies.size())
        throw ArchiveError("the checkpoint has another number of immersed rigid bodies");
    }
    last_step_ = steady() || steps_ == 0 ? &steady_step_ : &stepper_.last_step();
  }
  void write_final_output(const std::string& out_dir) const override {
    for (const FlowProbe& p : problem_.probes)
      if (p.type == FlowProbeType::line) write_line_probe(p, problem_, x_, out_dir + "/line_" + safe_file_name(p.name) + ".csv");
  }

  void add_run_fields(nlohmann::json& j, bool completed) const override;
  std::string summary() const override;

  std::string name() const override { return "flow"; }
  std::vector<WorldObject> objects() const override {
    std::vector<WorldObject> list{{problem_.name, "fluid", 0, static_cast<long>(problem_.model.mesh.node_count())}};
    if (problem_.immersed)
      for (size_t i = 0; i < problem_.immersed->model.solids.size(); ++i) {
        const FemSolid& s = problem_.immersed->model.solids[i];
        list.push_back({s.name, problem_.immersed->rigid_body_of(i) ? "rigid_body" : "solid", static_cast<long>(s.node_begin),
                        static_cast<long>(s.mesh.node_count())});
      }
    return list;
  }
  std::vector<StateArray> state_arrays() override {
    const NavierStokesModel& m = problem_.model;
    std::vector<StateArray> arrays{state_array("flow.solution", "", x_.data(), m.fields(), m.mesh.node_count(), true)};
    if (solids_) {
      const FemModel& solid = problem_.immersed->model;
      arrays.push_back(state_array("solid.displacement", "m", solids_->displacement.data(), solid.dim, solid.node_count, true));
      arrays.push_back(state_array("solid.velocity", "m/s", solids_->velocity.data(), solid.dim, solid.node_count, false));
    }
    return arrays;
  }
  std::map<std::string, double> stage_times() const override {
    // "assembly" is the fluid's cells; "solid_terms" the immersed solids' (a part of the assembly).
    if (!solids_) return {{"assembly", assembly_s_}, {"solve", solve_s_}};
    return {{"assembly", assembly_s_ - source_s_}, {"solid_terms", source_s_}, {"solve", solve_s_}};
  }

 private:
  bool steady() const { return problem_.integrator == FlowIntegrator::steady; }
  const ImmersedSolidState* immersed_state() const { return solids_ ? &*solids_ : nullptr; }
  void solve_steady(int threads);
  void step_transient(int threads);
  void account(const FlowSolveResult& r);
  void shift_to_mean_pressure();

  const Scene& scene_;
  const FlowProblem& problem_;
  int threads_;
  VectorX x_;
  Real time_ = 0;
  long steps_ = 0;
  FlowStepper stepper_;
  FlowLinearSolver solver_;
  const FlowTimeStep steady_step_;
  const FlowTimeStep* last_step_ = &steady_step_;  // the last step's scheme, for the reactions of boundary_force
  int last_iterations_ = 0, max_iterations_ = 0;
  long total_iterations_ = 0, picard_iterations_ = 0;
  double assembly_s_ = 0, solve_s_ = 0, source_s_ = 0;
  long retried_steps_ = 0;                                        // steps that needed substeps
  Real smallest_step_ = std::numeric_limits<Real>::infinity();  // s, the smallest substep taken
  std::optional<ImmersedSolidState> solids_;
  std::optional<ImmersedCoupling> coupling_;
  nlohmann::json continuation_ = nlohmann::json::array();
  std::optional<FlowFrameWriter> frames_;
};

void FlowEngine::account(const FlowSolveResult& r) {
  assembly_s_ += r.assembly_s;
  solve_s_ += r.solve_s;
  source_s_ += r.source_s;
  last_iterations_ = r.iterations + r.picard_iterations;
  total_iterations_ += r.iterations;
  picard_iterations_ += r.picard_iterations;
  max_iterations_ = std::max(max_iterations_, last_iterations_);
}

// "pressure_reference": {"mean": value}: shift the pressure so that its mean is the value.
void FlowEngine::shift_to_mean_pressure() {
  if (!problem_.mean_pressure) return;
  const NavierStokesModel& m = problem_.model;
  const Real shift = *problem_.mean_pressure - mean_pressure(m, x_);
  for (Index n = 0; n < m.mesh.node_count(); ++n) x_[m.dof(n, m.dim())] += shift;
}

void FlowEngine::solve_steady(int threads) {
  // Continuation: each viscosity's solution starts the next; the model's own comes last.
  std::vector<Real> viscosities = problem_.continuation;
  viscosities.push_back(problem_.model.viscosity);
  for (size_t stage = 0; stage < viscosities.size(); ++stage) {
    FlowSolveSettings settings = problem_.solve;
    settings.viscosity = viscosities[stage];
    settings.threads = threads;
    if (stage + 1 < viscosities.size()) settings.tolerance = std::max(settings.tolerance, problem_.continuation_tolerance);
    const FlowSolveResult r = stepper_.step(problem_.model, 0, 0, x_, solver_, settings);
    account(r);
    continuation_.push_back(
        {{"viscosity", viscosities[stage]}, {"newton_iterations", r.iterations}, {"picard_iterations", r.picard_iterations}});
    if (!r.converged)
      throw NumericalError(
          fmt::format("the steady solve of the fluid at viscosity {} Pa s failed: {}", viscosities[stage], r.failure));
  }
  shift_to_mean_pressure();
  ++steps_;
}

// One run-loop step. If its solve fails (Newton and Picard, or a solid leaving the mesh on the
// way), it is retried from the same start as 2, 4, ..., 2^max_step_halvings equal substeps: the
// immersed solids' and the stepper's states are restored with the fluid's. Every attempt's
// iterations and times are counted.
void FlowEngine::step_transient(int threads) {
  const Real dt = scene_.fem->dt;
  FlowSolveSettings settings = problem_.solve;
  settings.threads = threads;
  const VectorX start = x_;
  const std::optional<ImmersedSolidState> solids_start = solids_;
  const FlowStepper stepper_start = stepper_;
  FlowSolveResult total;
  int substeps = 1;
  for (int halvings = 0;; ++halvings, substeps *= 2) {
    std::string failure;
    for (int k = 0; k < substeps && failure.empty(); ++k) {
      FlowSolveResult r;
      try {  // a boundary value that is not finite, or a solid leaving the mesh, throws NumericalError naming it
        r = stepper_.step(problem_.model, time_ + k * dt / substeps, dt / substeps, x_, solver_, settings,
                          coupling_ ? &*coupling_ : nullptr);
      } catch (const NumericalError& e) {
        r.converged = false;
        r.failure = e.what();
      }
      total.iterations += r.iterations;
      total.picard_iterations += r.picard_iterations;
      total.assembly_s += r.assembly_s;
      total.solve_s += r.solve_s;
      total.source_s += r.source_s;
      if (!r.converged) failure = r.failure;
      else if (!x_.allFinite()) failure = "the velocity or pressure is not finite";
    }
    last_step_ = &stepper_.last_step();
    if (failure.empty()) break;
    x_ = start;
    if (solids_) *solids_ = *solids_start;
    stepper_ = stepper_start;
    last_step_ = &stepper_.last_step();
    if (halvings == problem_.max_step_halvings) {
      account(total);
      const std::string retried = substeps > 1 ? fmt::format(" (also in {} substeps of {:.6g} s)", substeps, dt / substeps) : "";
      throw NumericalError(
          fmt::format("step {} (t = {:.6g} s to {:.6g} s) failed{}: fluid: {}", steps_ + 1, time_, time_ + dt, retried, failure));
    }
  }
  if (substeps > 1) {
    ++retried_steps_;
    smallest_step_ = std::min(smallest_step_, dt / substeps);
  }
  total.converged = true;
  account(total);
  shift_to_mean_pressure();
  time_ += dt;
  ++steps_;
}

void FlowEngine::add_run_fields(nlohmann::json& j, bool /*completed*/) const {
  const NavierStokesModel& model = problem_.model;
  j["integrator"] = flow_integrator_name(problem_.integrator);
  j["counts"] = {{"fluid_nodes", model.mesh.node_count()}, {"cells", model.mesh.cell_count()},
                 {"unknowns", model.dof_count()}, {"free_unknowns", model.free_count}};
  // A distributed run (written by rank 0): how the rows were divided, and rank 0's share of cells.
  if (model.partition)
    j["partition"] = {{"rows_per_rank", model.partition->rows.counts}, {"cells_assembled_by_rank_0", model.partition->cells}};
  j["newton"] = {{"iterations", total_iterations_},    {"picard_iterations", picard_iterations_},
                 {"max_iterations_per_step", max_iterations_}, {"tolerance", problem_.solve.tolerance},
                 {"assembly_s", assembly_s_},           {"solve_s", solve_s_}};
  if (!steady()) {
    j["newton"]["retried_steps"] = retried_steps_;
    j["newton"]["smallest_step_s"] = retried_steps_ > 0 ? smallest_step_ : scene_.fem->dt;
  }
  j["linear_solver"] = {{"type", solver_.name()}};
  if (problem_.linear.method != FlowLinearMethod::direct) {
    const FlowLinearStatistics& ls = solver_.statistics();
    const bool gmres = problem_.linear.method == FlowLinearMethod::gmres;
    j["linear_solver"].update(nlohmann::json{{"solves", ls.solves},
                                             {gmres ? "gmres_iterations" : "krylov_iterations", ls.iterations},
                                             {gmres ? "max_gmres_iterations_per_solve" : "max_krylov_iterations_per_solve",
                                              ls.max_iterations},
                                             {"preconditioner_updates", ls.preconditioner_updates},
                                             {"preconditioner_s", ls.preconditioner_s},
                                             {"tolerance", problem_.linear.tolerance}});
    if (gmres) j["linear_solver"]["retries"] = ls.retries;
  }
  if (steady()) j["continuation"] = continuation_;
  if (problem_.immersed) {
    const FemModel& solid = problem_.immersed->model;
    Index cells = 0;
    for (const FemSolid& s : solid.solids) cells += s.mesh.cell_count();
    j["counts"]["solid_nodes"] = solid.node_count;
    j["counts"]["solid_cells"] = cells;
    j["newton"]["solid_terms_s"] = source_s_;
  }
}

std::string FlowEngine::summary() const {
  const NavierStokesModel& m = problem_.model;
  std::string s = fmt::format("scene '{}' ({}): solver fem ({}D fluid), integrator {}", scene_.name, scene_.file, m.dim(),
                              flow_integrator_name(problem_.integrator));
  if (!steady()) s += fmt::format(", dt {} s, duration {} s", scene_.fem->dt, scene_.duration);
  s += fmt::format("\n  fluid: {} nodes, {} {} cells, density {} kg/m^3, viscosity {} Pa s\n", m.mesh.node_count(),
                   m.mesh.cell_count(), element_name(m.mesh.element), m.density, m.viscosity);
  if (problem_.immersed)
    for (size_t i = 0; i < problem_.immersed->model.solids.size(); ++i) {
      const FemSolid& solid = problem_.immersed->model.solids[i];
      if (const ImmersedRigidBody* body = problem_.immersed->rigid_body_of(i))
        s += fmt::format("  immersed rigid body '{}': {} nodes, {} {} cells, density {} kg/m^3, coupling stiffness {:.4g} "
                         "Pa s/m^2\n",
                         solid.name, solid.mesh.node_count(), solid.mesh.cell_count(), element_name(solid.mesh.element),
                         solid.material.density, body->coupling_stiffness);
      else
        s += fmt::format("  immersed solid '{}': {} nodes, {} {} cells, density {} kg/m^3, viscosity {} Pa s\n", solid.name,
                         solid.mesh.node_count(), solid.mesh.cell_count(), element_name(solid.mesh.element),
                         solid.material.density, problem_.immersed->viscosity[i]);
    }
  s += fmt::format("  unknowns {} ({} free), Jacobian nonzeros {}, probes {}\n", m.dof_count(), m.free_count,
                   m.pattern.nonZeros(), problem_.probes.size());
  return s;
}

}  // namespace

std::unique_ptr<Engine> make_flow_engine(Scene& scene) { return std::make_unique<FlowEngine>(scene); }

}  // namespace moreau
