#include "krylov_solver.hpp"

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cmath>
#include <sstream>

#include "petsc_call.hpp"

namespace moreau::petsc_plugin {

static_assert(sizeof(PetscInt) == sizeof(int), "the plugin passes 32-bit indices to PETSc");
static_assert(std::is_same_v<PetscScalar, double>, "the plugin needs PETSc's real double build");

namespace {

// "-ksp_type gmres -pc_hypre_boomeramg_strong_threshold 0.5" with prefix "moreau1_flow_" becomes
// "-moreau1_flow_ksp_type gmres -moreau1_flow_pc_hypre_boomeramg_strong_threshold 0.5": a token is
// an option's name when it starts with '-' and a letter (not a negative number).
std::string with_prefix(const std::string& options, const std::string& prefix) {
  std::istringstream tokens(options);
  std::string token, out;
  while (tokens >> token) {
    if (!out.empty()) out += ' ';
    if (token.size() > 1 && token[0] == '-' && std::isalpha(static_cast<unsigned char>(token[1])))
      out += '-' + prefix + token.substr(1);
    else
      out += token;
  }
  return out;
}

// The rigid-body modes of a solid on its free unknowns (translations along each axis, rotations
// about each axis through the centroid), orthonormalized by modified Gram-Schmidt as
// MatNullSpaceCreate requires. They span the near-null space of the elasticity operator: smoothed
// aggregation builds its coarse spaces from them (Vanek, Mandel & Brezina 1996, Computing 56).
std::vector<std::vector<double>> rigid_body_modes(const UnknownLayout& layout) {
  const size_t n = layout.component.size();
  double centre[3] = {0, 0, 0};
  for (size_t i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k) centre[k] += layout.position[3 * i + k] / static_cast<double>(n);
  const int count = layout.dim == 2 ? 3 : 6;
  std::vector<std::vector<double>> modes(count, std::vector<double>(n, 0.0));
  for (size_t i = 0; i < n; ++i) {
    const int c = layout.component[i];
    const double x = layout.position[3 * i] - centre[0], y = layout.position[3 * i + 1] - centre[1],
                 z = layout.position[3 * i + 2] - centre[2];
    modes[c][i] = 1;  // translation along axis c
    if (layout.dim == 2) {
      modes[2][i] = c == 0 ? -y : x;  // rotation about z: (-y, x)
    } else {
      const double about_x[3] = {0, -z, y}, about_y[3] = {z, 0, -x}, about_z[3] = {-y, x, 0};
      modes[3][i] = about_x[c];
      modes[4][i] = about_y[c];
      modes[5][i] = about_z[c];
    }
  }
  for (int a = 0; a < count; ++a) {
    for (int b = 0; b < a; ++b) {
      double dot = 0;
      for (size_t i = 0; i < n; ++i) dot += modes[a][i] * modes[b][i];
      for (size_t i = 0; i < n; ++i) modes[a][i] -= dot * modes[b][i];
    }
    double norm = 0;
    for (double v : modes[a]) norm += v * v;
    norm = std::sqrt(norm);
    const double scale = norm > 1e-12 * std::sqrt(static_cast<double>(n)) ? 1 / norm : 0;
    for (double& v : modes[a]) v *= scale;
  }
  // A mode with nothing left after the others were taken out of it (every dof of a component
  // prescribed, or all nodes on one line) is not a direction: it is dropped.
  std::erase_if(modes, [](const std::vector<double>& mode) {
    return std::none_of(mode.begin(), mode.end(), [](double v) { return std::isfinite(v) && v != 0; });
  });
  return modes;
}

}  // namespace

KrylovSolver::KrylovSolver(const SolverSpec& spec, const UnknownLayout& layout) : spec_(spec), layout_(layout) {
  static std::atomic<int> solvers{0};
  prefix_ = "moreau" + std::to_string(++solvers) + "_" + spec.prefix;
  int rank = 0, ranks = 1;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  MPI_Comm_size(PETSC_COMM_WORLD, &ranks);
  if (!layout.owner.empty() && ranks > 1) {
    try {
      distribution_.emplace(layout.owner, rank, ranks);
    } catch (const std::invalid_argument& e) {
      throw PetscFailure(e.what());
    }
  }
  petsc_call(PetscOptionsInsertString(nullptr, with_prefix(spec.options, prefix_).c_str()), "the PETSc options");
  create_ksp();
}

// A new KSP from the options under this solver's prefix. A KSP is made again for a matrix of
// another pattern: a field split, once set up, keeps its blocks' index sets and patterns.
void KrylovSolver::create_ksp() {
  KSPDestroy(&ksp_);
  try {
    petsc_call(KSPCreate(communicator(), &ksp_), "KSPCreate");
    petsc_call(KSPSetOptionsPrefix(ksp_, prefix_.c_str()), "KSPSetOptionsPrefix");
    petsc_call(KSPSetTolerances(ksp_, spec_.relative_tolerance, spec_.absolute_tolerance, PETSC_DEFAULT,
                                spec_.max_iterations),
               "KSPSetTolerances");
    petsc_call(KSPSetFromOptions(ksp_), "the KSP's options");
  } catch (const PetscFailure&) {
    KSPDestroy(&ksp_);
    throw;
  }
}

KrylovSolver::~KrylovSolver() {
  PetscBool finalized = PETSC_TRUE;
  PetscFinalized(&finalized);
  if (finalized) return;  // at exit, after PETSc has gone: nothing left to free
  KSPDestroy(&ksp_);
  MatDestroy(&matrix_);
  VecDestroy(&b_);
  VecDestroy(&x_);
  VecScatterDestroy(&gather_all_);
  VecDestroy(&x_all_);
}

bool KrylovSolver::same_pattern(int n, const int* column_starts, const int* rows) const {
  if (!matrix_ || static_cast<int>(column_starts_.size()) != n + 1) return false;
  if (!std::equal(column_starts, column_starts + n + 1, column_starts_.begin())) return false;
  return std::equal(rows, rows + column_starts[n], rows_.begin());
}

// Column-ordered entries to rows: count the entries of each row, then walk the columns in order, so
// each row's columns come out sorted, as AIJ needs.
void KrylovSolver::create_matrix(int n, const int* column_starts, const int* rows) {
  const bool had_matrix = matrix_ != nullptr;
  const int entries = column_starts[n];
  column_starts_.assign(column_starts, column_starts + n + 1);
  rows_.assign(rows, rows + entries);
  std::vector<PetscInt> row_starts(n + 1, 0), columns(entries), next(n);
  for (int k = 0; k < entries; ++k) ++row_starts[rows[k] + 1];
  for (int r = 0; r < n; ++r) row_starts[r + 1] += row_starts[r];
  std::copy(row_starts.begin(), row_starts.end() - 1, next.begin());
  csr_position_.resize(entries);
  for (int j = 0; j < n; ++j)
    for (int k = column_starts[j]; k < column_starts[j + 1]; ++k) {
      const int position = next[rows[k]]++;
      columns[position] = j;
      csr_position_[k] = position;
    }
  csr_values_.assign(entries, 0.0);

  MatDestroy(&matrix_);
  VecDestroy(&b_);
  VecDestroy(&x_);
  if (had_matrix) create_ksp();
  petsc_call(MatCreate(PETSC_COMM_SELF, &matrix_), "MatCreate");
  petsc_call(MatSetSizes(matrix_, n, n, n, n), "MatSetSizes");
  petsc_call(MatSetType(matrix_, MATSEQAIJ), "MatSetType");
  petsc_call(MatSetOptionsPrefix(matrix_, prefix_.c_str()), "MatSetOptionsPrefix");
  petsc_call(MatSeqAIJSetPreallocationCSR(matrix_, row_starts.data(), columns.data(), csr_values_.data()),
             "MatSeqAIJSetPreallocationCSR");
  petsc_call(MatSetOption(matrix_, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE), "MatSetOption");
  petsc_call(MatCreateVecs(matrix_, &x_, &b_), "MatCreateVecs");
  attach_layout();
}

// This rank's rows of a distributed matrix: the entries of the column-ordered matrix in its own
// rows, renumbered to PETSc's rows and columns and sorted by column within each row (MPIAIJ's
// CSR). Rows of other ranks, complete or not, are left out.
void KrylovSolver::create_distributed_matrix(int n, const int* column_starts, const int* rows) {
  const RowDistribution& d = *distribution_;
  if (static_cast<int>(d.petsc_index.size()) != n)
    throw PetscFailure("the layout has " + std::to_string(d.petsc_index.size()) + " unknowns, the matrix " +
                       std::to_string(n));
  const bool had_matrix = matrix_ != nullptr;
  column_starts_.assign(column_starts, column_starts + n + 1);
  rows_.assign(rows, rows + column_starts[n]);
  const int local = static_cast<int>(d.owned.size());
  std::vector<int> local_row(n, -1);
  for (int i = 0; i < local; ++i) local_row[d.owned[i]] = i;
  std::vector<std::vector<std::pair<PetscInt, int>>> entries(local);  // (PETSc column, source entry)
  for (int j = 0; j < n; ++j)
    for (int k = column_starts[j]; k < column_starts[j + 1]; ++k)
      if (const int r = local_row[rows[k]]; r >= 0) entries[r].emplace_back(d.petsc_index[j], k);
  local_row_starts_.assign(1, 0);
  local_columns_.clear();
  local_source_.clear();
  for (auto& row : entries) {
    std::sort(row.begin(), row.end());
    for (const auto& [column, source] : row) {
      local_columns_.push_back(column);
      local_source_.push_back(source);
    }
    local_row_starts_.push_back(static_cast<PetscInt>(local_columns_.size()));
  }
  csr_values_.assign(local_columns_.size(), 0.0);

  MatDestroy(&matrix_);
  VecDestroy(&b_);
  VecDestroy(&x_);
  VecScatterDestroy(&gather_all_);
  VecDestroy(&x_all_);
  if (had_matrix) create_ksp();
  petsc_call(MatCreateMPIAIJWithArrays(PETSC_COMM_WORLD, local, local, n, n, local_row_starts_.data(),
                                       local_columns_.data(), csr_values_.data(), &matrix_),
             "MatCreateMPIAIJWithArrays");
  petsc_call(MatSetOptionsPrefix(matrix_, prefix_.c_str()), "MatSetOptionsPrefix");
  petsc_call(MatSetOption(matrix_, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE), "MatSetOption");
  petsc_call(MatCreateVecs(matrix_, &x_, &b_), "MatCreateVecs");
  petsc_call(VecScatterCreateToAll(x_, &gather_all_, &x_all_), "VecScatterCreateToAll");
  attach_layout();
}

// The field split's index sets and the near-null space, for preconditioners that use them (any other
// ignores them).
void KrylovSolver::attach_layout() {
  if (!layout_.field.empty()) {
    PC pc;
    petsc_call(KSPGetPC(ksp_, &pc), "KSPGetPC");
    // Each rank lists its own rows of each field, in PETSc's numbering.
    std::vector<PetscInt> velocity, pressure;
    for (size_t i = 0; i < layout_.field.size(); ++i) {
      if (distribution_ && layout_.owner[i] != distribution_->rank) continue;
      const PetscInt row = distribution_ ? distribution_->petsc_index[i] : static_cast<PetscInt>(i);
      (layout_.field[i] == 1 ? pressure : velocity).push_back(row);
    }
    IS sets[2] = {nullptr, nullptr};
    PetscErrorCode code =
        ISCreateGeneral(communicator(), static_cast<PetscInt>(velocity.size()), velocity.data(), PETSC_COPY_VALUES,
                        &sets[0]);
    if (!code)
      code = ISCreateGeneral(communicator(), static_cast<PetscInt>(pressure.size()), pressure.data(),
                             PETSC_COPY_VALUES, &sets[1]);
    if (!code) code = PCFieldSplitSetIS(pc, "u", sets[0]);
    if (!code) code = PCFieldSplitSetIS(pc, "p", sets[1]);
    ISDestroy(&sets[0]);
    ISDestroy(&sets[1]);
    petsc_call(code, "the field split's index sets");
  }
  if (!layout_.component.empty()) {
    const auto modes = rigid_body_modes(layout_);
    std::vector<Vec> vectors(modes.size(), nullptr);
    PetscErrorCode code = 0;
    for (size_t m = 0; m < modes.size() && !code; ++m) {
      code = MatCreateVecs(matrix_, &vectors[m], nullptr);
      PetscScalar* v = nullptr;
      if (!code) code = VecGetArray(vectors[m], &v);
      if (!code && distribution_)
        for (size_t i = 0; i < distribution_->owned.size(); ++i) v[i] = modes[m][distribution_->owned[i]];
      else if (!code)
        std::copy(modes[m].begin(), modes[m].end(), v);
      if (!code) code = VecRestoreArray(vectors[m], &v);
    }
    MatNullSpace space = nullptr;
    if (!code)
      code = MatNullSpaceCreate(communicator(), PETSC_FALSE, static_cast<PetscInt>(vectors.size()), vectors.data(),
                                &space);
    if (!code) code = MatSetNearNullSpace(matrix_, space);
    MatNullSpaceDestroy(&space);
    for (Vec& v : vectors) VecDestroy(&v);
    petsc_call(code, "the rigid-body modes");
  }
}

bool KrylovSolver::set_matrix(int n, const int* column_starts, const int* rows, const double* values,
                              std::string& failure) {
  const bool set = set_matrix_here(n, column_starts, rows, values, failure);
  if (!distribution_) return set;
  const int first_failed = first_failed_rank(!set);
  if (first_failed < 0) return true;
  if (set) {
    failure = "PETSc could not set up the preconditioner on rank " + std::to_string(first_failed);
    discard_setup();  // as the failed rank did: every rank builds its KSP and matrix afresh, together
  }
  return false;
}

// The ranks must agree on a failure, or those that succeeded would go on to collective calls the
// others never join. (This cannot help with an error raised inside a collective call, which the
// other ranks then wait in.)
int KrylovSolver::first_failed_rank(bool failed) const {
  int size = 0, rank = 0, first = 0;
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  const int mine = failed ? rank : size;
  if (MPI_Allreduce(&mine, &first, 1, MPI_INT, MPI_MIN, PETSC_COMM_WORLD) != MPI_SUCCESS) return rank;
  return first == size ? -1 : first;
}

bool KrylovSolver::set_matrix_here(int n, const int* column_starts, const int* rows, const double* values,
                                   std::string& failure) {
  try {
    if (!ksp_) create_ksp();
    const size_t laid_out = layout_.field.empty() ? layout_.component.size() : layout_.field.size();
    if (laid_out != 0 && laid_out != static_cast<size_t>(n))
      throw PetscFailure("the layout has " + std::to_string(laid_out) + " unknowns, the matrix " + std::to_string(n));
    if (distribution_) {
      if (!same_pattern(n, column_starts, rows)) create_distributed_matrix(n, column_starts, rows);
      for (size_t k = 0; k < local_source_.size(); ++k) csr_values_[k] = values[local_source_[k]];
      petsc_call(MatUpdateMPIAIJWithArray(matrix_, csr_values_.data()), "MatUpdateMPIAIJWithArray");
      petsc_call(KSPSetOperators(ksp_, matrix_, matrix_), "KSPSetOperators");
      petsc_call(KSPSetUp(ksp_), "setting up the preconditioner");
      return true;
    }
    if (!same_pattern(n, column_starts, rows)) create_matrix(n, column_starts, rows);
    PetscScalar* stored;
    petsc_call(MatSeqAIJGetArray(matrix_, &stored), "MatSeqAIJGetArray");
    for (int k = 0; k < column_starts[n]; ++k) stored[csr_position_[k]] = values[k];
    petsc_call(MatSeqAIJRestoreArray(matrix_, &stored), "MatSeqAIJRestoreArray");
    petsc_call(KSPSetOperators(ksp_, matrix_, matrix_), "KSPSetOperators");
    petsc_call(KSPSetUp(ksp_), "setting up the preconditioner");
    return true;
  } catch (const PetscFailure& e) {
    failure = e.what();
    discard_setup();
    return false;
  }
}

// A setup that failed leaves the KSP half built (a field split without its blocks, which PETSc
// would dereference at the next setup): the next set_matrix starts from a new KSP and matrix. The
// broken KSP is dropped without KSPDestroy, which crashes on it too (PETSc 3.18, in
// KSPReset_FGMRES after a failed field-split setup); this leaks one KSP per failed setup.
void KrylovSolver::discard_setup() {
  VecScatterDestroy(&gather_all_);
  VecDestroy(&x_all_);
  VecDestroy(&b_);
  VecDestroy(&x_);
  column_starts_.clear();
  ksp_ = nullptr;
  matrix_ = nullptr;  // still referenced by the dropped KSP
}

std::vector<std::string> KrylovSolver::unused_options() const {
  PetscInt count = 0;
  char** names = nullptr;
  char** values = nullptr;
  std::vector<std::string> unused;
  if (PetscOptionsLeftGet(nullptr, &count, &names, &values) != 0) return unused;
  for (PetscInt i = 0; i < count; ++i) {
    const std::string name = names[i];
    if (name.rfind(prefix_, 0) == 0) unused.push_back("-" + name.substr(prefix_.size()));
  }
  PetscOptionsLeftRestore(nullptr, &count, &names, &values);
  return unused;
}

SolveReport KrylovSolver::solve(const double* b, double* x) {
  SolveReport report;
  try {
    if (distribution_) {
      solve_distributed(b, x, report);
    } else {
      petsc_call(VecPlaceArray(b_, const_cast<double*>(b)), "VecPlaceArray");
      if (const PetscErrorCode placed = VecPlaceArray(x_, x)) {
        VecResetArray(b_);
        petsc_call(placed, "VecPlaceArray");
      }
      const PetscErrorCode code = KSPSolve(ksp_, b_, x_);
      VecResetArray(b_);
      VecResetArray(x_);
      petsc_call(code, "KSPSolve");
      read_report(report);
    }
  } catch (const PetscFailure& e) {
    report.converged = false;
    report.error = true;
    report.reason = e.what();
  }
  if (distribution_) {
    const int first_failed = first_failed_rank(report.error);
    if (first_failed >= 0 && !report.error) {
      report.converged = false;
      report.error = true;
      report.reason = "PETSc failed in the solve on rank " + std::to_string(first_failed);
    }
  }
  if (report.error) discard_setup();
  return report;
}

// Each rank gives its rows of b; every rank receives the whole solution.
void KrylovSolver::solve_distributed(const double* b, double* x, SolveReport& report) {
  const RowDistribution& d = *distribution_;
  PetscScalar* local = nullptr;
  petsc_call(VecGetArray(b_, &local), "VecGetArray");
  for (size_t i = 0; i < d.owned.size(); ++i) local[i] = b[d.owned[i]];
  petsc_call(VecRestoreArray(b_, &local), "VecRestoreArray");
  petsc_call(KSPSolve(ksp_, b_, x_), "KSPSolve");
  petsc_call(VecScatterBegin(gather_all_, x_, x_all_, INSERT_VALUES, SCATTER_FORWARD), "VecScatterBegin");
  petsc_call(VecScatterEnd(gather_all_, x_, x_all_, INSERT_VALUES, SCATTER_FORWARD), "VecScatterEnd");
  const PetscScalar* all = nullptr;
  petsc_call(VecGetArrayRead(x_all_, &all), "VecGetArrayRead");
  for (size_t i = 0; i < d.petsc_index.size(); ++i) x[i] = all[d.petsc_index[i]];
  petsc_call(VecRestoreArrayRead(x_all_, &all), "VecRestoreArrayRead");
  read_report(report);
}

void KrylovSolver::read_report(SolveReport& report) const {
  KSPConvergedReason reason;
  petsc_call(KSPGetConvergedReason(ksp_, &reason), "KSPGetConvergedReason");
  petsc_call(KSPGetIterationNumber(ksp_, &report.iterations), "KSPGetIterationNumber");
  petsc_call(KSPGetResidualNorm(ksp_, &report.residual), "KSPGetResidualNorm");
  report.converged = reason > 0;
  report.reason = KSPConvergedReasons[reason];
}

std::string KrylovSolver::describe() const {
  if (!ksp_) return "?";
  KSPType ksp_type = nullptr;
  PCType pc_type = nullptr;
  PC pc;
  KSPGetType(ksp_, &ksp_type);
  KSPGetPC(ksp_, &pc);
  PCGetType(pc, &pc_type);
  return std::string(ksp_type ? ksp_type : "?") + "+" + (pc_type ? pc_type : "?");
}

}  // namespace moreau::petsc_plugin
