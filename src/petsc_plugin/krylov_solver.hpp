#pragma once
// One PETSc KSP with its matrix: the matrix arrives in compressed sparse column form, is stored
// as PETSc's AIJ (compressed rows), and keeps its pattern between Newton iterations, so only the
// values are copied and the preconditioner's symbolic setup is reused. On one process the matrix is
// sequential (SEQAIJ); in a distributed run (a layout with owners, several ranks) each rank keeps
// its own rows of an MPIAIJ matrix in PETSc's numbering (row_distribution.hpp).
#include <petscksp.h>

#include <optional>
#include <vector>

#include "moreau/fem/petsc/petsc_plugin_api.hpp"
#include "row_distribution.hpp"

namespace moreau::petsc_plugin {

class KrylovSolver final : public LinearSolver {
 public:
  /// Throws PetscFailure if the KSP cannot be created.
  KrylovSolver(const SolverSpec& spec, const UnknownLayout& layout);
  ~KrylovSolver() override;
  KrylovSolver(const KrylovSolver&) = delete;
  KrylovSolver& operator=(const KrylovSolver&) = delete;

  bool set_matrix(int n, const int* column_starts, const int* rows, const double* values,
                  std::string& failure) override;
  SolveReport solve(const double* b, double* x) override;
  std::string describe() const override;
  std::vector<std::string> unused_options() const override;

 private:
  // set_matrix on this rank alone (false with `failure` on a PETSc error).
  bool set_matrix_here(int n, const int* column_starts, const int* rows, const double* values, std::string& failure);
  void discard_setup();
  // Distributed: the lowest rank whose `failed` is true, or -1 (a collective call: every rank makes it).
  int first_failed_rank(bool failed) const;
  bool same_pattern(int n, const int* column_starts, const int* rows) const;
  void create_ksp();
  void create_matrix(int n, const int* column_starts, const int* rows);
  void create_distributed_matrix(int n, const int* column_starts, const int* rows);
  void attach_layout();
  void solve_distributed(const double* b, double* x, SolveReport& report);
  void read_report(SolveReport& report) const;
  MPI_Comm communicator() const { return distribution_ ? PETSC_COMM_WORLD : PETSC_COMM_SELF; }

  SolverSpec spec_;
  UnknownLayout layout_;
  std::string prefix_;  // unique to this solver: spec.prefix after a process-wide counter
  KSP ksp_ = nullptr;
  Mat matrix_ = nullptr;
  Vec b_ = nullptr, x_ = nullptr;
  // The pattern as given (to recognise it again) and, per stored entry in column order, its
  // position in the row-ordered values PETSc holds.
  std::vector<int> column_starts_, rows_, csr_position_;
  std::vector<PetscScalar> csr_values_;
  // Distributed: the numbering, this rank's rows (CSR in PETSc's numbering, each entry's position
  // in the engine's column-ordered values) and the scatter that gives every rank the solution.
  std::optional<RowDistribution> distribution_;
  std::vector<PetscInt> local_row_starts_, local_columns_;
  std::vector<int> local_source_;
  VecScatter gather_all_ = nullptr;
  Vec x_all_ = nullptr;
};

}  // namespace moreau::petsc_plugin
