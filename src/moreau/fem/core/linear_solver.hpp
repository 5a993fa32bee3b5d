#pragma once
// Sparse direct solves of the FEM engine's tangent systems through Eigen's SuiteSparse wrappers.
// The tangent of a hyperelastic solid is symmetric; near equilibrium and with enough Dirichlet
// conditions it is positive definite and CHOLMOD's supernodal Cholesky factorizes it. Where it is
// not (buckling, a free-floating body's rigid modes, compression past a limit point) the
// factorization reports it and UMFPACK's LU takes over. The symbolic analysis is done once per
// sparsity pattern and reused by every later factorization.
#include <Eigen/CholmodSupport>
#include <Eigen/UmfPackSupport>
#include <memory>
#include <string>
#include <vector>

#include "moreau/fem/petsc/petsc_plugin_api.hpp"
#include "moreau/fem/solids/fem_model.hpp"

namespace moreau {

class ArchiveWriter;
class ArchiveReader;

/// UMFPACK's LU of a square sparse matrix; the symbolic analysis is done for the first matrix and
/// reused for every later one with the same sparsity (a matrix with another pattern, such as a
/// flow's with an immersed solid that moved to other cells, is analysed again).
class SparseLuSolver {
 public:
  SparseLuSolver();
  /// False if the matrix is singular.
  bool factorize(const SparseMatrix& A);
  VectorX solve(const VectorX& b) const { return lu_.solve(b); }

 private:
  Eigen::UmfPackLU<SparseMatrix> lu_;
  std::vector<int> analyzed_outer_, analyzed_inner_;  // the analysed pattern (compressed column starts, rows)
};

/// How a solid's tangent systems are solved.
struct SolidLinearSettings {
  bool petsc = false;                  // false: CHOLMOD, UMFPACK where it is not positive definite
  std::string preconditioner = "amg";  // petsc: a name of solid_petsc_preconditioners()
  Real tolerance = 1e-8;               // petsc: the Krylov solve's relative residual
  int max_iterations = 1000;           // petsc: Krylov iterations per solve
  std::string petsc_options;           // petsc: PETSc options after the preset's
  std::string options_warning;         // petsc: the options PETSc did not read when the scene was checked
};

/// The PETSc options of a solid's solver: the preset's, then the user's. `symmetric`: the solver
/// of symmetric tangents (static and midpoint steps); else the energy-momentum scheme's, or the
/// one CG falls back to (GMRES around the same multigrid, or LU in place of Cholesky).
std::string solid_solver_options(const SolidLinearSettings& settings, bool symmetric);

/// The free unknowns of a solid model as the PETSc plugin sees them: per free dof, its component
/// and its node's reference position (for the rigid-body modes), and in a distributed model
/// (model.partition) the rank that owns its row.
petsc_plugin::UnknownLayout solid_unknown_layout(const FemModel& model);

class SparseSymmetricSolver {
 public:
  SparseSymmetricSolver();
  ~SparseSymmetricSolver();
  /// Solves with PETSc from now on: a symmetric K with the preset's Krylov method, any other with
  /// right-preconditioned GMRES around the same preconditioner (LU for "cholesky").
  void use_petsc(const SolidLinearSettings& settings, petsc_plugin::UnknownLayout layout);
  /// Factorizes K; false if neither Cholesky nor LU succeeds (a singular K). A K that is not
  /// symmetric (`symmetric` false) goes to LU directly.
  bool factorize(const SparseMatrix& K, bool symmetric = true);
  /// Solves K x = b with the last factorization (direct only).
  VectorX solve(const VectorX& b) const;
  /// Solves K x = b with the last K factorized (which must still be alive: PETSc may set it up
  /// again for GMRES when CG meets an indefinite multigrid cycle); false, with failure() saying
  /// why, if the Krylov solve did not converge.
  bool solve(const VectorX& b, VectorX& x);
  /// "cholmod", "umfpack" or "petsc cg+gamg": what solved with the last K.
  const std::string& method() const { return method_; }
  /// Why the last factorize or solve failed ("" if neither did).
  const std::string& failure() const { return failure_; }
  /// Krylov iterations over all solves and the most in one (petsc only).
  long krylov_iterations() const { return krylov_iterations_; }
  int max_krylov_iterations() const { return max_krylov_iterations_; }

  /// Checkpoints: the Krylov counters and, with PETSc, whether CG has given way to GMRES (a
  /// restored run must go on with the solver the uninterrupted one would use). The direct
  /// solvers keep nothing between steps but their symbolic analyses, which depend on the pattern.
  void save(ArchiveWriter& out) const;
  void load(ArchiveReader& in);

 private:
  struct Petsc;
  bool factorize_petsc(const SparseMatrix& K, bool symmetric);

  Eigen::CholmodSupernodalLLT<SparseMatrix, Eigen::Lower> cholesky_;
  SparseLuSolver lu_;
  bool cholesky_analyzed_ = false;
  std::string method_, failure_;
  std::unique_ptr<Petsc> petsc_;
  long krylov_iterations_ = 0;
  int max_krylov_iterations_ = 0;
};

}  // namespace moreau
