#include "moreau/fem/petsc/petsc_option_check.hpp"

#include <vector>

#include "moreau/fem/petsc/petsc_matrix.hpp"

namespace moreau {

PetscOptionCheck check_petsc_options(petsc_plugin::Backend& backend, const std::string& options, PetscSystemKind kind) {
  constexpr int n = 6;
  const int fields = kind == PetscSystemKind::flow ? 4 : 3;
  const auto node = [&](int i, int j, int k) { return (i * n + j) * n + k; };
  petsc_plugin::UnknownLayout layout;
  std::vector<Eigen::Triplet<Real, int>> entries;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k) {
        const int a = node(i, j, k);
        std::vector<int> neighbours;
        if (i > 0) neighbours.push_back(node(i - 1, j, k));
        if (i + 1 < n) neighbours.push_back(node(i + 1, j, k));
        if (j > 0) neighbours.push_back(node(i, j - 1, k));
        if (j + 1 < n) neighbours.push_back(node(i, j + 1, k));
        if (k > 0) neighbours.push_back(node(i, j, k - 1));
        if (k + 1 < n) neighbours.push_back(node(i, j, k + 1));
        for (int f = 0; f < fields; ++f) {
          const int row = a * fields + f;
          entries.emplace_back(row, row, static_cast<Real>(neighbours.size()) + 1);
          for (int b : neighbours) entries.emplace_back(row, b * fields + f, -1.0);
          if (kind == PetscSystemKind::flow) {
            layout.field.push_back(f == 3 ? 1 : 0);
          } else {
            layout.component.push_back(f);
            layout.position.insert(layout.position.end(), {double(i) / n, double(j) / n, double(k) / n});
          }
        }
      }
  const int unknowns = n * n * n * fields;
  SparseMatrix A(unknowns, unknowns);
  A.setFromTriplets(entries.begin(), entries.end());
  A.makeCompressed();

  PetscOptionCheck check;
  std::unique_ptr<petsc_plugin::LinearSolver> solver =
      backend.make_solver({.prefix = "scene_check_", .options = options}, layout, check.failure);
  if (!solver) return check;
  if (!set_petsc_matrix(*solver, A, check.failure)) return check;
  // One solve too: block Jacobi reads its blocks' options when it first applies them.
  const std::vector<double> b(static_cast<size_t>(unknowns), 1.0);
  std::vector<double> x(b.size(), 0.0);
  const petsc_plugin::SolveReport report = solver->solve(b.data(), x.data());
  if (report.error) {
    check.failure = report.reason;
    return check;
  }
  check.unused = solver->unused_options();
  return check;
}

}  // namespace moreau
