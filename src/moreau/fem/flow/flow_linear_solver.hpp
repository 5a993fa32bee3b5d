#pragma once
// The linear solves inside the flow's Newton and Picard iterations, J dx = -R on the free dofs.
//
// direct: UMFPACK's sparse LU (SparseLuSolver). The default: in 2D and on small 3D meshes it is
//   the fastest (the 128^2 cavity factorizes in 0.2 s), but in 3D its fill grows like n^(4/3)
//   in memory and n^2 in time (a 20^3 hex8 cavity: 6 s and 1.4 GB per factorization).
// gmres: restarted GMRES (Saad & Schultz 1986, SIAM J. Sci. Stat. Comput. 7; Eigen's unsupported
//   implementation, the Householder variant of Walker 1988, SIAM J. Sci. Stat. Comput. 9),
//   left-preconditioned by a dual-threshold incomplete LU, ILUT(drop_tolerance, fill_factor)
//   (Saad 1994, Numer. Linear Algebra Appl. 1; Eigen's IncompleteLUT on an AMD ordering, which
//   is computed once per sparsity pattern). Entries below drop_tolerance times the row's norm are
//   dropped, and each row keeps its (fill_factor * average entries per row of J) / 2 largest
//   entries in L and as many in U. The PSPG term gives the pressure rows a diagonal, so the
//   equal-order saddle point needs no special ordering.
//   Newton then becomes an inexact Newton method (Dembo, Eisenstat & Steihaug 1982, SIAM J.
//   Numer. Anal. 19): each correction solves J dx = -R until the preconditioned residual has
//   dropped by `tolerance`; Newton's own convergence test is unchanged. With tau frozen Newton
//   converges linearly at a rate of 1e-1 ... 1e-2 per iteration anyway, so a forcing term of
//   1e-3 costs no Newton iterations (measured on the 3D cavity, docs/performance.md).
//   The ILU is lagged: it is computed for the first Jacobian and then only when a solve needed
//   more than refresh_ratio times max(10, the iterations of the first solve after the last
//   refresh), when a solve failed (it is retried once with a fresh ILU), or when the matrix's
//   size or number of entries (its pattern) changed. Jacobians of successive Newton iterations, continuation stages and time steps differ
//   little, and one ILU costs as much as ~100 GMRES iterations.
// petsc: a PETSc Krylov solver and preconditioner (PETSc's KSP and PC, loaded as a plugin; see
//   fem/petsc/petsc_presets.hpp for what each "preconditioner" means). Inexact Newton like gmres,
//   with `tolerance` relative to the true (unpreconditioned) residual; the preconditioner is
//   built again for every Jacobian, its symbolic setup kept while the pattern is.
// direct and gmres are serial; all are deterministic. In a distributed run (mpirun) only petsc
// solves, across the ranks.
#include <memory>
#include <string>
#include <vector>

#include "moreau/fem/core/linear_solver.hpp"

namespace moreau {

class ArchiveWriter;
class ArchiveReader;

enum class FlowLinearMethod { direct, gmres, petsc };

struct FlowLinearSettings {
  FlowLinearMethod method = FlowLinearMethod::direct;
  // gmres and petsc:
  Real tolerance = 1e-3;       // relative reduction of the residual per solve
  int max_iterations = 1000;   // Krylov iterations per solve
  int restart = 50;            // Krylov vectors kept before a restart (memory: restart x unknowns)
  // petsc only:
  std::string preconditioner = "fieldsplit";  // a name of flow_petsc_preconditioners()
  std::string petsc_options;                  // PETSc options after the preset's ("-ksp_monitor")
  std::string options_warning;                // the options PETSc did not read when the scene was checked
  // gmres only:
  Real drop_tolerance = 1e-2;  // ILUT: entries below this times the row's norm are dropped
  int fill_factor = 2;         // ILUT: entries kept per row of L plus U, relative to J's average row
  Real refresh_ratio = 2;      // ILU recomputed when a solve needs this times max(10, its first solve's iterations)
};

/// What the linear solves cost so far (gmres and petsc; the direct solver leaves them 0; for petsc
/// a preconditioner update is the setup for one Jacobian).
struct FlowLinearStatistics {
  long solves = 0;                   // linear systems solved (or attempted)
  int retries = 0;                   // solves repeated with a fresh ILU after a lagged one failed
  long iterations = 0;               // GMRES iterations over all solves
  int max_iterations = 0;            // the most in one solve
  int preconditioner_updates = 0;    // ILU computations
  double preconditioner_s = 0;       // s spent in them
};

class FlowLinearSolver {
 public:
  explicit FlowLinearSolver(const FlowLinearSettings& settings = {});
  ~FlowLinearSolver();

  /// The unknowns of the next Jacobians: per dof, its index among the free dofs (-1 if
  /// prescribed), with `fields` dofs per node of which the last is the pressure. Needed before the
  /// first factorize by petsc's field split (without it, PETSc refuses a field split); the other
  /// methods ignore it. `owner`, in a distributed run: per free dof, the rank that owns its row
  /// (the Jacobians then need to be right in this rank's rows only).
  void set_layout(const std::vector<Index>& free_index, int fields, Index free_count,
                  const std::vector<int>* owner = nullptr);

  /// Takes the Jacobian of the next solve; J must stay alive and unchanged until then. False if
  /// it is singular (direct) or its incomplete factorization breaks down (gmres).
  bool factorize(const SparseMatrix& J);
  /// Solves J dx = b; false (with failure() set) if GMRES does not reach its tolerance even with a
  /// fresh preconditioner.
  bool solve(const VectorX& b, VectorX& dx);

  const std::string& failure() const { return failure_; }
  const FlowLinearStatistics& statistics() const { return statistics_; }
  /// "umfpack", "gmres+ilut" or "petsc fgmres+fieldsplit" (PETSc's KSP and PC types).
  std::string name() const;

  /// Checkpoints: the statistics and, for gmres, the lagged ILU — as the matrix it was computed
  /// from, computed again on load (the same bits: the factorization is serial and its ordering
  /// depends on the pattern only) — and the counters that decide its next refresh. The direct
  /// solver keeps nothing between solves but its symbolic analysis, which depends on the pattern.
  void save(ArchiveWriter& out) const;
  void load(ArchiveReader& in);

 private:
  struct Iterative;
  struct Petsc;
  bool factorize_petsc(const SparseMatrix& J);
  bool solve_petsc(const VectorX& b, VectorX& dx);
  bool refresh_preconditioner();
  bool needs_refresh() const;

  FlowLinearSettings settings_;
  SparseLuSolver lu_;
  std::unique_ptr<Iterative> iterative_;
  std::unique_ptr<Petsc> petsc_;
  const SparseMatrix* matrix_ = nullptr;
  FlowLinearStatistics statistics_;
  std::string failure_;
};

}  // namespace moreau
