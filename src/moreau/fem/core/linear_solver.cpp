#include "moreau/fem/core/linear_solver.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cassert>

#include "moreau/fem/petsc/petsc_matrix.hpp"
#include "moreau/fem/petsc/petsc_plugin_loader.hpp"
#include "moreau/fem/petsc/petsc_presets.hpp"
#include "moreau/fem/solids/solid_partition.hpp"
#include "moreau/io/binary_archive.hpp"

namespace moreau {

petsc_plugin::UnknownLayout solid_unknown_layout(const FemModel& model) {
  petsc_plugin::UnknownLayout layout;
  if (model.partition) layout.owner = model.partition->rows.owner;
  layout.dim = model.dim;
  layout.component.resize(model.free_count);
  layout.position.resize(3 * static_cast<size_t>(model.free_count));
  for (Index d = 0; d < model.dof_count(); ++d) {
    const Index row = model.free_index[d];
    if (row < 0) continue;
    layout.component[row] = d % model.dim;
    const Vec3 X = model.reference_position(d / model.dim);
    for (int k = 0; k < 3; ++k) layout.position[3 * row + k] = X[k];
  }
  return layout;
}

std::string solid_solver_options(const SolidLinearSettings& settings, bool symmetric) {
  const std::string& name = settings.preconditioner;
  std::string options = solid_petsc_options(symmetric || name != "cholesky" ? name : "lu");
  if (!symmetric) options += " -ksp_type " + std::string(name == "amg" ? "gmres -ksp_pc_side right" : "preonly");
  return options + " " + settings.petsc_options;
}

// Two PETSc solvers, made when first needed: one for symmetric tangents (the static and midpoint
// ones), one for the energy-momentum scheme's nonsymmetric ones.
struct SparseSymmetricSolver::Petsc {
  SolidLinearSettings settings;
  petsc_plugin::UnknownLayout layout;
  std::unique_ptr<petsc_plugin::LinearSolver> symmetric, general;
  petsc_plugin::LinearSolver* last = nullptr;
  const SparseMatrix* matrix = nullptr;  // the last K, alive until the solve that follows it
  bool cg_indefinite = false;            // CG met an indefinite multigrid cycle: GMRES from then on
};

SparseSymmetricSolver::SparseSymmetricSolver() {
  // An indefinite tangent is an expected outcome (UMFPACK takes over), not a warning to print.
  cholesky_.cholmod().print = 0;
}

SparseSymmetricSolver::~SparseSymmetricSolver() = default;

void SparseSymmetricSolver::use_petsc(const SolidLinearSettings& settings, petsc_plugin::UnknownLayout layout) {
  petsc_ = std::make_unique<Petsc>();
  petsc_->settings = settings;
  petsc_->layout = std::move(layout);
}

bool SparseSymmetricSolver::factorize_petsc(const SparseMatrix& K, bool symmetric) {
  Petsc& p = *petsc_;
  if (p.cg_indefinite) symmetric = false;
  auto& solver = symmetric ? p.symmetric : p.general;
  if (!solver) {
    petsc_plugin::SolverSpec spec;
    spec.prefix = symmetric ? "solid_" : "solid_general_";
    spec.options = solid_solver_options(p.settings, symmetric);
    spec.relative_tolerance = p.settings.tolerance;
    spec.max_iterations = p.settings.max_iterations;
    solver = petsc_backend().make_solver(spec, p.layout, failure_);
    if (!solver) return false;
  }
  p.last = solver.get();
  p.matrix = &K;
  method_ = "petsc " + solver->describe();
  return set_petsc_matrix(*solver, K, failure_);
}

bool SparseSymmetricSolver::solve(const VectorX& b, VectorX& x) {
  if (!petsc_) {
    x = solve(b);
    return true;
  }
  x = VectorX::Zero(b.size());
  petsc_plugin::SolveReport report = petsc_->last->solve(b.data(), x.data());
  krylov_iterations_ += report.iterations;
  max_krylov_iterations_ = std::max(max_krylov_iterations_, report.iterations);
  // CG needs a positive definite preconditioner, and multigrid's Chebyshev smoothers, tuned by
  // estimates of the extreme eigenvalues, are not always one on a tangent far from the reference
  // configuration (seen on the sheared 20^3 block at its third load step): the solve is repeated
  // with the GMRES solver, as the direct path falls back from Cholesky to LU, and GMRES solves
  // every later tangent of the run too. (Symmetric SOR smoothers, which would keep the cycle
  // positive definite, broke down on a 40^3 block.)
  if (!report.converged && report.reason.find("INDEFINITE") != std::string::npos && petsc_->last == petsc_->symmetric.get()) {
    petsc_->cg_indefinite = true;
    if (!factorize_petsc(*petsc_->matrix, false)) return false;
    petsc_->symmetric.reset();  // its multigrid hierarchy is not needed again
    x.setZero();
    report = petsc_->last->solve(b.data(), x.data());
    krylov_iterations_ += report.iterations;
    max_krylov_iterations_ = std::max(max_krylov_iterations_, report.iterations);
  }
  if (report.converged) return true;
  if (report.error) {
    failure_ = "PETSc failed in the solve: " + report.reason;
    return false;
  }
  failure_ = fmt::format(
      "PETSc's {} stopped with {} after {} iterations (residual {:.2e}, tolerance {:.1e} relative); raise "
      "settings.linear_solver.max_iterations, or choose another \"preconditioner\"",
      petsc_->last->describe(), report.reason, report.iterations, report.residual, petsc_->settings.tolerance);
  return false;
}

bool SparseSymmetricSolver::factorize(const SparseMatrix& K, bool symmetric) {
  failure_.clear();
  if (petsc_) return factorize_petsc(K, symmetric);
  if (symmetric && !cholesky_analyzed_) {
    cholesky_.analyzePattern(K);
    cholesky_analyzed_ = true;
  }
  if (symmetric) cholesky_.factorize(K);
  if (symmetric && cholesky_.info() == Eigen::Success) {
    method_ = "cholmod";
    return true;
  }
  method_ = "umfpack";
  return lu_.factorize(K);
}

SparseLuSolver::SparseLuSolver() {
  // No iterative refinement: every caller is a Newton iteration, which refines by itself; the
  // default two refinement steps cost 3x the plain solve (0.055 s vs 0.016 s on the 128^2 cavity)
  // for a residual of 1e-15 instead of 3e-15.
  lu_.umfpackControl()(UMFPACK_IRSTEP) = 0;
}

bool SparseLuSolver::factorize(const SparseMatrix& A) {
  // Comparing the pattern costs one pass over the indices, far less than the factorization.
  const int* outer = A.outerIndexPtr();
  const int* inner = A.innerIndexPtr();
  const size_t columns = static_cast<size_t>(A.outerSize()) + 1, entries = static_cast<size_t>(A.nonZeros());
  const bool same = A.isCompressed() && analyzed_outer_.size() == columns && analyzed_inner_.size() == entries &&
                    std::equal(outer, outer + columns, analyzed_outer_.begin()) &&
                    std::equal(inner, inner + entries, analyzed_inner_.begin());
  if (!same) {
    lu_.analyzePattern(A);
    if (A.isCompressed()) {
      analyzed_outer_.assign(outer, outer + columns);
      analyzed_inner_.assign(inner, inner + entries);
    } else {
      analyzed_outer_.clear();
    }
  }
  lu_.factorize(A);
  return lu_.info() == Eigen::Success;
}

VectorX SparseSymmetricSolver::solve(const VectorX& b) const {
  assert(!petsc_ && "a PETSc solve can fail: use solve(b, x)");
  if (method_ == "cholmod") return cholesky_.solve(b);
  return lu_.solve(b);
}

void SparseSymmetricSolver::save(ArchiveWriter& out) const {
  const bool cg_indefinite = petsc_ && petsc_->cg_indefinite;
  archive(out, std::tie(krylov_iterations_, max_krylov_iterations_, cg_indefinite));
}

void SparseSymmetricSolver::load(ArchiveReader& in) {
  bool cg_indefinite = false;
  auto fields = std::tie(krylov_iterations_, max_krylov_iterations_, cg_indefinite);
  unarchive(in, fields);
  if (cg_indefinite && !petsc_) throw ArchiveError("the checkpoint's solid was solved by PETSc, this scene's is not");
  if (petsc_ && petsc_->cg_indefinite != cg_indefinite) {
    petsc_->cg_indefinite = cg_indefinite;
    petsc_->symmetric.reset();
    petsc_->general.reset();
    petsc_->last = nullptr;
  }
}

}  // namespace moreau
