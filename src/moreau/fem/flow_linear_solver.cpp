#include "moreau/fem/flow_linear_solver.hpp"

#include <fmt/format.h>

#include <Eigen/IterativeLinearSolvers>
#include <algorithm>
#include <chrono>
#include <unsupported/Eigen/IterativeSolvers>

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
  Eigen::GMRES<SparseMatrix, HeldIlut> gmres;
  bool fresh = false;          // the ILU was computed from the Jacobian being solved
  int iterations_after_refresh = 0;
  int last_iterations = 0;
  bool last_failed = false;
};

FlowLinearSolver::FlowLinearSolver(const FlowLinearSettings& settings) : settings_(settings) {
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

std::string FlowLinearSolver::name() const { return iterative_ ? "gmres+ilut" : "umfpack"; }

bool FlowLinearSolver::refresh_preconditioner() {
  Iterative& it = *iterative_;
  const auto start = std::chrono::steady_clock::now();
  it.ilu.compute(*matrix_);
  statistics_.preconditioner_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ++statistics_.preconditioner_updates;
  it.fresh = true;
  it.iterations_after_refresh = -1;  // set by the next solve
  if (it.ilu.info() != Eigen::Success) {
    failure_ = "the incomplete LU of the flow Jacobian broke down (a zero row: is every dof coupled?)";
    return false;
  }
  return true;
}

bool FlowLinearSolver::factorize(const SparseMatrix& J) {
  failure_.clear();
  matrix_ = &J;
  if (!iterative_) {
    if (lu_.factorize(J)) return true;
    failure_ = "the flow Jacobian is singular (is the pressure fixed somewhere, or an outflow given?)";
    return false;
  }
  Iterative& it = *iterative_;
  it.fresh = false;
  it.gmres.compute(J);  // takes J; the held ILU is left as it is
  const bool first = statistics_.preconditioner_updates == 0;
  const bool slowed = it.iterations_after_refresh > 0 &&
                      it.last_iterations > settings_.refresh_ratio * std::max(it.iterations_after_refresh, 10);
  if (first || slowed || it.last_failed) return refresh_preconditioner();
  return true;
}

bool FlowLinearSolver::solve(const VectorX& b, VectorX& dx) {
  if (!iterative_) {
    dx = lu_.solve(b);
    return true;
  }
  Iterative& it = *iterative_;
  for (;;) {
    dx = it.gmres.solve(b);
    const int iterations = static_cast<int>(it.gmres.iterations());
    ++statistics_.solves;
    statistics_.iterations += iterations;
    statistics_.max_iterations = std::max(statistics_.max_iterations, iterations);
    it.last_iterations = iterations;
    if (it.iterations_after_refresh < 0) it.iterations_after_refresh = iterations;
    it.last_failed = it.gmres.info() != Eigen::Success;
    if (!it.last_failed) return true;
    // A lagged preconditioner may have gone stale: try once more with a fresh one.
    if (!it.fresh) {
      if (!refresh_preconditioner()) return false;
      continue;
    }
    failure_ = fmt::format(
        "GMRES did not reach its tolerance {:.1e} in {} iterations (reached {:.2e}); raise "
        "settings.linear_solver.max_iterations or fill_factor, lower drop_tolerance, or use \"type\": \"direct\"",
        settings_.tolerance, iterations, it.gmres.error());
    return false;
  }
}

}  // namespace moreau
