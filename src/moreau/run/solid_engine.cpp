// The FEM engine for solids, director rigid bodies and joints: static load steps, or time steps
// of the implicit midpoint rule or the energy-momentum scheme. One step (SolidEngine::step):
//   static      Newton equilibrium at t + dt (load stepping)
//   dynamic     joints present: one coupled Newton system of solids, bodies and joint multipliers
//               no joints: the solids' Newton step, then each free rigid body's constrained
//               midpoint step under gravity
#include "moreau/run/engines.hpp"

#include <fmt/format.h>

#include <optional>

#include "moreau/errors.hpp"
#include "moreau/fem/bodies/coupled_step.hpp"
#include "moreau/fem/solids/solid_partition.hpp"
#include "moreau/fem/scene/fem_output.hpp"
#include "moreau/fem/solids/fem_assembly.hpp"
#include "moreau/io/binary_archive.hpp"
#include "moreau/io/probe_csv.hpp"
#include "moreau/run/state_arrays.hpp"
#include "moreau/scene/scene.hpp"

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

class SolidEngine final : public Engine {
 public:
  explicit SolidEngine(Scene& scene);

  double time() const override { return run_.solids.time; }
  double dt() const override { return problem_.dt; }
  int requested_threads() const override { return problem_.threads; }
  void step(int threads) override;
  std::vector<std::string> warnings() const override {
    if (problem_.linear.options_warning.empty()) return {};
    return {problem_.linear.options_warning};
  }

  std::vector<std::string> probe_columns() const override {
    return probe_table_columns(problem_.probes, [&](const FemProbe& p) { return fem_probe_columns(p, problem_.model.dim); });
  }
  void sample_probes(std::vector<Real>& values) const override {
    for (const FemProbe& p : problem_.probes) evaluate_fem_probe(p, problem_, run_, last_iterations_, values);
  }
  void open_frames(const std::string& out_dir, const std::string& scene_name, FrameSeries resume) override {
    frames_.emplace(problem_, out_dir, scene_name, std::move(resume));
  }
  void write_frame() override { frames_->write(run_); }
  FrameSeries frame_series() const override { return frames_ ? frames_->series() : FrameSeries{}; }

  // The mass matrix is assembled again at the first step; the linear solvers' symbolic analyses
  // depend on the (fixed) pattern only, and every Newton iteration factorizes afresh (the
  // solver's checkpoint holds its counters and its choice of Krylov method).
  void save_state(ArchiveWriter& out) const override {
    archive(out, std::tie(run_, steps_, last_iterations_, max_iterations_, total_iterations_));
    solver_.save(out);
  }
  void load_state(ArchiveReader& in) override {
    auto fields = std::tie(run_, steps_, last_iterations_, max_iterations_, total_iterations_);
    unarchive(in, fields);
    solver_.load(in);
  }

  void add_run_fields(nlohmann::json& j, bool completed) const override;
  std::string summary() const override;

  std::string name() const override { return "fem"; }
  std::vector<WorldObject> objects() const override {
    std::vector<WorldObject> list;
    for (const FemSolid& s : problem_.model.solids) list.push_back({s.name, "solid", s.node_begin, s.mesh.node_count()});
    for (size_t b = 0; b < problem_.rigid_bodies.size(); ++b)
      list.push_back({problem_.rigid_bodies[b].name, "rigid_body", static_cast<long>(b), 1});
    return list;
  }
  std::vector<StateArray> state_arrays() override {
    const FemModel& m = problem_.model;
    return {state_array("solid.displacement", "m", run_.solids.u.data(), m.dim, m.node_count, true),
            state_array("solid.velocity", "m/s", run_.solids.v.data(), m.dim, m.node_count, true),
            state_array("body.director_state", "", run_.bodies, static_cast<long>(run_.bodies.size()), true)};
  }
  std::map<std::string, double> stage_times() const override { return {{"assembly", assembly_s_}, {"solve", solve_s_}}; }

 private:
  NewtonResult advance(const NewtonSettings& newton);

  const Scene& scene_;
  const FemProblem& problem_;
  FemRunState run_;
  long steps_ = 0;
  SparseMatrix mass_;  // the consistent mass matrix, assembled at the first dynamic step
  SparseSymmetricSolver solver_;
  SparseLuSolver coupled_;
  int last_iterations_ = 0, max_iterations_ = 0;
  long total_iterations_ = 0;
  double assembly_s_ = 0, solve_s_ = 0;
  std::optional<FemFrameWriter> frames_;
};

SolidEngine::SolidEngine(Scene& scene) : scene_(scene), problem_(*scene.fem) {
  const FemModel& model = problem_.model;
  for (const FemRigidBody& b : problem_.rigid_bodies) run_.bodies.push_back(b.initial);
  FemDynamicState& state = run_.solids;
  state = initial_dynamic_state(model);
  for (Index d = 0; d < model.dof_count(); ++d)
    if (model.free_index[d] >= 0) state.v[d] = problem_.initial_velocity[d];
  // A static solve starts from the reference configuration; its first load step's predictor
  // carries the prescribed values in (moving only the boundary nodes would invert cells).
  if (problem_.integrator == FemIntegrator::static_load_steps) {
    state.u.setZero();
    state.v.setZero();
  }
  VectorX force;
  state.energy = assemble_internal_forces(model, state.u, force, nullptr).energy;
  if (problem_.linear.petsc) solver_.use_petsc(problem_.linear, solid_unknown_layout(model));
}

NewtonResult SolidEngine::advance(const NewtonSettings& newton) {
  const FemModel& model = problem_.model;
  FemDynamicState& state = run_.solids;
  const Real dt = problem_.dt;
  NewtonResult r;
  if (problem_.integrator == FemIntegrator::static_load_steps) {
    r = solve_static(model, state.time + dt, state.u, solver_, newton);
    if (r.converged) {
      state.time += dt;
      state.energy = r.energy;
    }
    return r;
  }
  if (mass_.size() == 0 && model.free_count > 0) mass_ = assemble_mass_matrix(model);
  const StepRule rule = problem_.integrator == FemIntegrator::midpoint ? StepRule::midpoint : StepRule::energy_momentum;
  if (!problem_.joints.empty()) return step_coupled(problem_, mass_, rule, dt, run_, coupled_, newton);
  if (model.dof_count() > 0) {
    r = step_dynamic(model, mass_, rule, dt, state, solver_, newton);
  } else {
    r.converged = true;
    state.time += dt;
  }
  // Free rigid bodies: the constrained midpoint step (energy and angular momentum conserving for
  // either integrator) under gravity, by the discrete null-space form (six unknowns per body;
  // tested against the multiplier form, which the coupled step with joints uses).
  for (size_t b = 0; b < run_.bodies.size() && r.converged; ++b) {
    const DirectorBody& body = problem_.rigid_bodies[b].body;
    const NewtonResult rb = step_director_body_reduced(body, dt, body.mass * problem_.gravity, Vec3::Zero(), run_.bodies[b], newton);
    if (!rb.converged) {
      r.converged = false;
      r.failure = fmt::format("rigid body '{}': {}", problem_.rigid_bodies[b].name, rb.failure);
    }
    r.iterations += rb.iterations;
  }
  return r;
}

void SolidEngine::step(int threads) {
  NewtonSettings newton = problem_.newton;
  newton.threads = threads;
  const Real t = run_.solids.time;
  NewtonResult r;
  try {  // a load or prescribed value that is not finite throws NumericalError naming itself and t
    r = advance(newton);
  } catch (const NumericalError& e) {
    r.converged = false;
    r.failure = e.what();
  }
  if (!r.converged)
    throw NumericalError(fmt::format("step {} (t = {:.6g} s to {:.6g} s) failed: {}", steps_ + 1, t, t + problem_.dt, r.failure));
  ++steps_;
  assembly_s_ += r.assembly_s;
  solve_s_ += r.solve_s;
  last_iterations_ = r.iterations;
  total_iterations_ += r.iterations;
  max_iterations_ = std::max(max_iterations_, r.iterations);
}

void SolidEngine::add_run_fields(nlohmann::json& j, bool completed) const {
  const FemModel& model = problem_.model;
  j["integrator"] = integrator_name(problem_.integrator);
  Index cells = 0;
  for (const FemSolid& s : model.solids) cells += s.mesh.cell_count();
  j["counts"] = {{"solids", model.solids.size()}, {"rigid_bodies", problem_.rigid_bodies.size()},
                 {"joints", problem_.joints.size()}, {"nodes", model.node_count},
                 {"cells", cells},                {"dofs", model.dof_count()},
                 {"free_dofs", model.free_count}};
  j["newton"] = {{"iterations", total_iterations_},
                 {"max_iterations_per_step", max_iterations_},
                 {"tolerance", problem_.newton.tolerance},
                 {"assembly_s", assembly_s_},
                 {"solve_s", solve_s_},
                 {"last_linear_solver", problem_.joints.empty() ? solver_.method() : std::string("umfpack (coupled)")}};
  if (problem_.linear.petsc)
    j["linear_solver"] = {{"type", "petsc"},
                          {"preconditioner", problem_.linear.preconditioner},
                          {"tolerance", problem_.linear.tolerance},
                          {"krylov_iterations", solver_.krylov_iterations()},
                          {"max_krylov_iterations_per_solve", solver_.max_krylov_iterations()}};
  // A distributed run (written by rank 0): how the rows were divided, and rank 0's share of cells.
  if (model.partition)
    j["partition"] = {{"rows_per_rank", model.partition->rows.counts},
                      {"cells_assembled_by_rank_0", model.partition->assembled_cells}};
  if (completed) {
    Real kinetic = kinetic_energy(model, run_.solids.v);
    for (size_t b = 0; b < run_.bodies.size(); ++b) kinetic += kinetic_energy(problem_.rigid_bodies[b].body, run_.bodies[b]);
    j["final_energy_j"] = {{"kinetic", kinetic}, {"elastic", run_.solids.energy}};
  }
}

std::string SolidEngine::summary() const {
  const FemProblem& p = problem_;
  const FemModel& m = p.model;
  std::string s = fmt::format("scene '{}' ({}): solver fem ({}D), integrator {}, dt {} s, duration {} s\n", scene_.name,
                              scene_.file, m.dim, integrator_name(p.integrator), p.dt, scene_.duration);
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

}  // namespace

std::unique_ptr<Engine> make_solid_engine(Scene& scene) { return std::make_unique<SolidEngine>(scene); }

}  // namespace moreau
