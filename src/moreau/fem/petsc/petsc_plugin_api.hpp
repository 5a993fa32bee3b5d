#pragma once
// The interface between the engine and its PETSc plugin, libmoreau_petsc.so.
//
// PETSc and the MPI library under it are 107 shared libraries that take 85 ms to load; the engine
// loads them (dlopen) only for a scene that asks for "linear_solver": {"type": "petsc"}, so every
// other run starts as fast as before and the engine builds without PETSc's headers. This header is
// compiled into both sides; it holds plain data and abstract classes only, and the version below
// is checked when the plugin is loaded. Matrices cross it in compressed sparse column form (Eigen's
// default layout), vectors as contiguous doubles.
//
// A distributed run (`mpirun -np N moreau run`) keeps the whole mesh and state on every rank; the
// unknowns' rows are divided among the ranks (UnknownLayout::owner), each rank hands the solver
// its own rows of the matrix, and every rank receives the whole solution. The plugin starts MPI
// (through PETSc) and lends the engine the few collective operations it needs (Communicator).
#include <memory>
#include <string>
#include <vector>

namespace moreau::petsc_plugin {

/// Raised when the engine and the plugin were built from different versions of this header.
constexpr int kInterfaceVersion = 3;

/// What is known about the unknowns of the system beyond its matrix, for the preconditioners that
/// need it. Every vector is empty or has one entry per unknown (row).
struct UnknownLayout {
  /// Per unknown, its field: for a flow 0 for a velocity component, 1 for the pressure (the
  /// field-split preconditioner's two blocks); unused for a solid.
  std::vector<int> field;
  /// Per unknown of a solid: the displacement component (0, 1, 2) and the position of its node,
  /// from which the rigid-body modes (the near-null space of elasticity for algebraic multigrid)
  /// are built. Unused for a flow.
  std::vector<int> component;
  std::vector<double> position;  // 3 per unknown, m
  int dim = 3;
  /// Per unknown, the MPI rank that owns its row in a distributed run; empty on one process. The
  /// solver then takes only this rank's rows of each matrix (the others' may be missing or
  /// incomplete) and returns the whole solution on every rank.
  std::vector<int> owner;
};

/// The processes of the run: MPI's world when started by mpirun, else this process alone.
class Communicator {
 public:
  virtual ~Communicator() = default;
  virtual int rank() const = 0;
  virtual int size() const = 0;
  /// Every rank gives counts[rank] values; every rank receives all of them, rank 0's first
  /// (MPI_Allgatherv). `all` holds the sum of `counts`.
  virtual void all_gather(const double* mine, const int* counts, double* all) const = 0;
};

/// A Krylov solver with its preconditioner, set up from a PETSc options string.
struct SolverSpec {
  /// The options prefix of this solver's KSP ("flow_", "solid_"): the user's options are given
  /// without it and the plugin adds it, so two solvers never read each other's options.
  std::string prefix;
  /// PETSc options, "-ksp_type gmres -pc_type hypre ..." (without the prefix): the preset's, then
  /// the user's, so the user's win.
  std::string options;
  double relative_tolerance = 1e-8;  // of the residual norm the KSP's norm type measures
  double absolute_tolerance = 1e-50;
  int max_iterations = 10000;
};

struct SolveReport {
  bool converged = false;
  int iterations = 0;
  double residual = 0;  // the final residual norm KSP monitored
  std::string reason;   // PETSc's converged or diverged reason, as its name, or its error message
  bool error = false;   // PETSc raised an error (reason holds its message); set_matrix starts afresh
};

class LinearSolver {
 public:
  virtual ~LinearSolver() = default;
  /// Takes a square matrix of n rows in compressed sparse column form (column_starts: n + 1
  /// entries; rows and values: one per stored entry). A matrix with the pattern of the previous one
  /// only updates the values and keeps the preconditioner's symbolic setup. False, with `failure`
  /// set, if the preconditioner cannot be built; in a distributed run the ranks agree (false on
  /// every rank when it fails on one).
  virtual bool set_matrix(int n, const int* column_starts, const int* rows, const double* values,
                          std::string& failure) = 0;
  /// Solves A x = b for the last matrix from a zero initial guess (Newton's corrections have no
  /// better one). b and x are whole vectors on every rank; in a distributed run each rank reads
  /// its own rows of b, and x is the same on every rank.
  virtual SolveReport solve(const double* b, double* x) = 0;
  /// The KSP and PC types actually used ("gmres+fieldsplit"), after the first set_matrix.
  virtual std::string describe() const = 0;
  /// This solver's options that PETSc has not read (misspelt, or for a solver or preconditioner that
  /// was not created), as given ("-fieldsplit_u_pc_typ"); inner solvers read theirs when the
  /// preconditioner is built (set_matrix) or first applied (solve).
  virtual std::vector<std::string> unused_options() const = 0;
};

class Backend {
 public:
  virtual ~Backend() = default;
  /// A new solver; `failure` set and nullptr returned if the options are not understood.
  virtual std::unique_ptr<LinearSolver> make_solver(const SolverSpec& spec, const UnknownLayout& layout,
                                                    std::string& failure) = 0;
  /// PETSc's version, "3.18.5", and whether it was built with hypre and MUMPS.
  virtual std::string version() const = 0;
  /// The run's processes (MPI was started with the backend).
  virtual const Communicator& world() const = 0;
};

}  // namespace moreau::petsc_plugin

/// The plugin's one exported symbol: the backend (PETSc initialized on the first call), or nullptr
/// with an explanation in `failure` if `interface_version` is not the plugin's.
extern "C" moreau::petsc_plugin::Backend* moreau_petsc_backend(int interface_version, std::string* failure);
