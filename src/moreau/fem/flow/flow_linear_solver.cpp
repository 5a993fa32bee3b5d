#include "moreau/fem/flow/flow_linear_solver.hpp"

#include <fmt/format.h>

#include <Eigen/IterativeLinearSolvers>
#include <algorithm>
#include <chrono>
#include <unsupported/Eigen/IterativeSolvers>

#include "moreau/fem/petsc/petsc_matrix.hpp"
#include "moreau/fem/petsc/petsc_plugin_loader.hpp"
#include "moreau/fem/petsc/petsc_presets.hpp"
#include "moreau/io/binary_archive.hpp"

namespace moreau {

namespace {

// Eigen's iterative solvers recompute their preconditioner in every compute(A). This one only
// applies an ILU that FlowLinearSolver computes when it chooses, so one ILU can serve several
// Jacobians.
class HeldIlut {
 public:
  HeldIlut() = default;
  template <class M> HeldIlut& analyzePattern(const M&) { return *this; }
  template <class M> HeldIlut& factorize(const M&) { return *this; }
  template <class M> HeldIlut& compute(const M&) { return *this; }
  template <class B> auto solve(const B& b) const { return ilu->solve(b); }
  Eigen::ComputationInfo info() const { return Eigen::Success; }

  const Eigen::IncompleteLUT<Real>* ilu = nullptr;
};

}  // namespace

struct FlowLinearSolver::Iterative {
  Eigen::IncompleteLUT<Real> ilu;
  SparseMatrix ilu_source;       // the matrix the held ILU was computed from (for checkpoints)
  Eigen::GMRES<SparseMatrix, HeldIlut> gmres;
  bool ilu_valid = false;        // the held ILU was computed without breaking down
  bool fresh = false;            // ... from the Jacobian being solved
  Index rows = -1, entries = -1; // the size and pattern it was computed for
  int baseline_iterations = -1;  // of the first solve after the last refresh (-1: none yet)
  int last_iterations = 0;
  bool last_failed = false;
};

struct FlowLinearSolver::Petsc {
  petsc_plugin::UnknownLayout layout;   // per free dof, 0 velocity or 1 pressure
  std::unique_ptr<petsc_plugin::LinearSolver> solver;  // made at the first factorize
};

FlowLinearSolver::FlowLinearSolver(const FlowLinearSettings& settings) : settings_(settings) {
  if (settings_.method == FlowLinearMethod::petsc) petsc_ = std::make_unique<Petsc>();
  if (settings_.method == FlowLinearMethod::gmres) {
    iterative_ = std::make_unique<Iterative>();
    iterative_->ilu.setDroptol(settings_.drop_tolerance);
    iterative_->ilu.setFillfactor(settings_.fill_factor);
    iterative_->gmres.preconditioner().ilu = &iterative_->ilu;
    iterative_->gmres.set_restart(settings_.restart);
    iterative_->gmres.setTolerance(settings_.tolerance);
    iterative_->gmres.setMaxIterations(settings_.max_iterations);
  }
}

FlowLinearSolver::~FlowLinearSolver() = default;

std::string FlowLinearSolver::name() const {
  if (petsc_) return "petsc " + (petsc_->solver ? petsc_->solver->describe() : settings_.preconditioner);
  return iterative_ ? "gmres+ilut" : "umfpack";
}

void FlowLinearSolver::set_layout(const std::vector<Index>& free_index, int fields, Index free_count,
                                  const std::vector<int>* owner) {
  if (!petsc_) return;
  std::vector<int> field(free_count, 0);
  for (size_t dof = 0; dof < free_index.size(); ++dof)
    if (free_index[dof] >= 0 && static_cast<int>(dof % fields) == fields - 1) field[free_index[dof]] = 1;
  std::vector<int> owners = owner ? *owner : std::vector<int>{};
  if (field == petsc_->layout.field && owners == petsc_->layout.owner) return;
  petsc_->layout.field = std::move(field);
  petsc_->layout.owner = std::move(owners);
  petsc_->solver.reset();  // its index sets were of the old unknowns
}

bool FlowLinearSolver::factorize_petsc(const SparseMatrix& J) {
  Petsc& p = *petsc_;
  if (!p.solver) {
    petsc_plugin::SolverSpec spec;
    spec.prefix = "flow_";
    spec.options = flow_petsc_options(settings_.preconditioner, settings_.restart) + " " + settings_.petsc_options;
    spec.relative_tolerance = settings_.tolerance;
    spec.max_iterations = settings_.max_iterations;
    p.solver = petsc_backend().make_solver(spec, p.layout, failure_);
    if (!p.solver) return false;
  }
  const auto start = std::chrono::steady_clock::now();
  const bool built = set_petsc_matrix(*p.solver, J, failure_);
  statistics_.preconditioner_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ++statistics_.preconditioner_updates;
  return built;
}

bool FlowLinearSolver::solve_petsc(const VectorX& b, VectorX& dx) {
  dx = VectorX::Zero(b.size());
  const petsc_plugin::SolveReport report = petsc_->solver->solve(b.data(), dx.data());
  ++statistics_.solves;
  statistics_.iterations += report.iterations;
  statistics_.max_iterations = std::max(statistics_.max_iterations, report.iterations);
  if (report.converged) return true;
  if (report.error) {
    failure_ = "PETSc failed in the solve: " + report.reason;
    return false;
  }
  failure_ = fmt::format(
      "PETSc's {} stopped with {} after {} iterations (residual {:.2e}, tolerance {:.1e} relative); raise "
      "settings.linear_solver.max_iterations, or choose another \"preconditioner\" or \"type\"",
      petsc_->solver->describe(), report.reason, report.iterations, report.residual, settings_.tolerance);
  return false;
}

bool FlowLinearSolver::refresh_preconditioner() {
  Iterative& state = *iterative_;
  const auto start = std::chrono::steady_clock::now();
  // The AMD ordering depends on the pattern only: computed again only when that changed.
  const bool same_pattern = state.rows == matrix_->rows() && state.entries == matrix_->nonZeros();
  if (!same_pattern) state.ilu.analyzePattern(*matrix_);
  state.ilu.factorize(*matrix_);
  state.ilu_source = *matrix_;
  statistics_.preconditioner_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ++statistics_.preconditioner_updates;
  state.rows = matrix_->rows();
  state.entries = matrix_->nonZeros();
  state.baseline_iterations = -1;
  state.ilu_valid = state.ilu.info() == Eigen::Success;
  state.fresh = state.ilu_valid;
  if (!state.ilu_valid) {
    failure_ = "the incomplete LU of the flow Jacobian broke down (a zero row: is every dof coupled?)";
    return false;
  }
  return true;
}

bool FlowLinearSolver::needs_refresh() const {
  const Iterative& state = *iterative_;
  if (!state.ilu_valid || state.last_failed) return true;
  if (state.rows != matrix_->rows() || state.entries != matrix_->nonZeros()) return true;
  return state.baseline_iterations >= 0 &&
         state.last_iterations > settings_.refresh_ratio * std::max(state.baseline_iterations, 10);
}

bool FlowLinearSolver::factorize(const SparseMatrix& J) {
  failure_.clear();
  matrix_ = &J;
  if (petsc_) return factorize_petsc(J);
  if (!iterative_) {
    if (lu_.factorize(J)) return true;
    failure_ = "the flow Jacobian is singular (is the pressure fixed somewhere, or an outflow given?)";
    return false;
  }
  Iterative& state = *iterative_;
  state.fresh = false;
  state.gmres.compute(J);  // takes J; the held ILU is left as it is
  if (needs_refresh()) return refresh_preconditioner();
  return true;
}

bool FlowLinearSolver::solve(const VectorX& b, VectorX& dx) {
  if (petsc_) return solve_petsc(b, dx);
  if (!iterative_) {
    dx = lu_.solve(b);
    return true;
  }
  Iterative& state = *iterative_;
  ++statistics_.solves;
  for (;;) {
    dx = state.gmres.solve(b);
    const int iterations = static_cast<int>(state.gmres.iterations());
    statistics_.iterations += iterations;
    statistics_.max_iterations = std::max(statistics_.max_iterations, iterations);
    state.last_iterations = iterations;
    if (state.baseline_iterations < 0) state.baseline_iterations = iterations;
    state.last_failed = state.gmres.info() != Eigen::Success;
    if (!state.last_failed) return true;
    // A lagged preconditioner may have gone stale: try once more with a fresh one.
    if (!state.fresh) {
      ++statistics_.retries;
      if (!refresh_preconditioner()) return false;
      continue;
    }
    failure_ = fmt::format(
        "GMRES did not reach its tolerance {:.1e} in {} iterations (reached {:.2e}); raise "
        "settings.linear_solver.max_iterations or fill_factor, lower drop_tolerance, or use \"type\": \"direct\"",
        settings_.tolerance, iterations, state.gmres.error());
    return false;
  }
}

// The counters carry over; preconditioner_s, a wall time, is of the run that measured it.
void FlowLinearSolver::save(ArchiveWriter& out) const {
  const FlowLinearStatistics& t = statistics_;
  archive(out, std::tie(t.solves, t.retries, t.iterations, t.max_iterations, t.preconditioner_updates));
  if (!iterative_) return;
  const Iterative& s = *iterative_;
  archive(out, std::tie(s.ilu_source, s.ilu_valid, s.fresh, s.rows, s.entries, s.baseline_iterations, s.last_iterations,
                        s.last_failed));
}

void FlowLinearSolver::load(ArchiveReader& in) {
  FlowLinearStatistics& t = statistics_;
  auto counters = std::tie(t.solves, t.retries, t.iterations, t.max_iterations, t.preconditioner_updates);
  unarchive(in, counters);
  if (!iterative_) return;
  Iterative& s = *iterative_;
  auto fields = std::tie(s.ilu_source, s.ilu_valid, s.fresh, s.rows, s.entries, s.baseline_iterations, s.last_iterations,
                         s.last_failed);
  unarchive(in, fields);
  if (s.rows >= 0) {
    s.ilu.analyzePattern(s.ilu_source);
    s.ilu.factorize(s.ilu_source);
  }
}

}  // namespace moreau
