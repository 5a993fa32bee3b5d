#include "moreau/fem/core/cell_sparsity.hpp"

#include <algorithm>

namespace moreau {

std::vector<std::vector<Index>> colour_cells(const FemMesh& mesh) {
  // Each node keeps the colours its cells have taken.
  std::vector<std::vector<int>> used(mesh.node_count());
  std::vector<std::vector<Index>> colours;
  std::vector<char> taken;
  for (Index e = 0; e < mesh.cell_count(); ++e) {
    const Index* c = mesh.cell(e);
    taken.assign(colours.size() + 1, 0);
    for (int a = 0; a < mesh.nodes_per_cell(); ++a)
      for (int colour : used[c[a]]) taken[colour] = 1;
    int colour = 0;
    while (taken[colour]) ++colour;
    if (colour >= static_cast<int>(colours.size())) colours.resize(colour + 1);
    colours[colour].push_back(e);
    for (int a = 0; a < mesh.nodes_per_cell(); ++a) used[c[a]].push_back(colour);
  }
  return colours;
}

namespace {

// Calls f(local row, local column, free row, free column) for the free pairs of cell e.
template <class F>
void free_pairs(const FemMesh& mesh, Index e, Index node_begin, int fields, const std::vector<Index>& free_index, F f) {
  const Index* c = mesh.cell(e);
  const int n = fields * mesh.nodes_per_cell();
  auto free_of = [&](int local) { return free_index[(node_begin + c[local / fields]) * fields + local % fields]; };
  for (int r = 0; r < n; ++r) {
    const Index row = free_of(r);
    if (row < 0) continue;
    for (int q = 0; q < n; ++q) {
      const Index col = free_of(q);
      if (col >= 0) f(r, q, row, col);
    }
  }
}

}  // namespace

void add_cell_couplings(const FemMesh& mesh, Index node_begin, int fields, const std::vector<Index>& free_index,
                        std::vector<Eigen::Triplet<Real, int>>& entries) {
  for (Index e = 0; e < mesh.cell_count(); ++e)
    free_pairs(mesh, e, node_begin, fields, free_index, [&](int, int, Index row, Index col) { entries.emplace_back(row, col, 0.0); });
}

std::vector<Index> cell_slots(const FemMesh& mesh, Index node_begin, int fields, const std::vector<Index>& free_index,
                              const SparseMatrix& pattern) {
  const int n = fields * mesh.nodes_per_cell();
  std::vector<Index> slots(static_cast<size_t>(mesh.cell_count()) * n * n, -1);
  const int* outer = pattern.outerIndexPtr();
  const int* inner = pattern.innerIndexPtr();
  for (Index e = 0; e < mesh.cell_count(); ++e)
    free_pairs(mesh, e, node_begin, fields, free_index, [&](int r, int q, Index row, Index col) {
      const int* end = inner + outer[col + 1];
      const int* at = std::lower_bound(inner + outer[col], end, row);
      if (at != end && *at == row) slots[static_cast<size_t>(e) * n * n + r * n + q] = static_cast<Index>(at - inner);
    });
  return slots;
}

Eigen::VectorXd gather_free(const std::vector<Index>& free_index, Index free_count, const Eigen::VectorXd& full) {
  Eigen::VectorXd free(free_count);
  for (size_t d = 0; d < free_index.size(); ++d)
    if (free_index[d] >= 0) free[free_index[d]] = full[d];
  return free;
}

void add_free(const std::vector<Index>& free_index, const Eigen::VectorXd& free, Eigen::VectorXd& full) {
  for (size_t d = 0; d < free_index.size(); ++d)
    if (free_index[d] >= 0) full[d] += free[free_index[d]];
}

}  // namespace moreau
