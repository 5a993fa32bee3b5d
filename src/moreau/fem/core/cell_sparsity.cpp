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

NodeGraph node_graph(const std::vector<MeshNodes>& meshes, Index node_count, bool with_self) {
  // Node -> cells incidence (compressed), then each node's neighbours collected with a marker.
  std::vector<Index> cell_start(static_cast<size_t>(node_count) + 1, 0);
  for (const MeshNodes& m : meshes)
    for (Index e = 0; e < m.mesh->cell_count(); ++e)
      for (int a = 0; a < m.mesh->nodes_per_cell(); ++a) ++cell_start[m.node_begin + m.mesh->cell(e)[a] + 1];
  for (Index a = 0; a < node_count; ++a) cell_start[a + 1] += cell_start[a];
  std::vector<std::pair<const MeshNodes*, Index>> cells_of(cell_start[node_count]);
  std::vector<Index> next(cell_start.begin(), cell_start.end() - 1);
  for (const MeshNodes& m : meshes)
    for (Index e = 0; e < m.mesh->cell_count(); ++e)
      for (int a = 0; a < m.mesh->nodes_per_cell(); ++a) cells_of[next[m.node_begin + m.mesh->cell(e)[a]]++] = {&m, e};
  NodeGraph graph;
  graph.start.assign(1, 0);
  std::vector<Index> marked(static_cast<size_t>(node_count), -1);
  for (Index a = 0; a < node_count; ++a) {
    const size_t first = graph.neighbour.size();
    for (Index k = cell_start[a]; k < cell_start[a + 1]; ++k) {
      const auto [m, e] = cells_of[k];
      for (int b = 0; b < m->mesh->nodes_per_cell(); ++b) {
        const Index node = m->node_begin + m->mesh->cell(e)[b];
        if (marked[node] == a || (node == a && !with_self)) continue;
        marked[node] = a;
        graph.neighbour.push_back(node);
      }
    }
    std::sort(graph.neighbour.begin() + static_cast<std::ptrdiff_t>(first), graph.neighbour.end());
    graph.start.push_back(static_cast<Index>(graph.neighbour.size()));
  }
  return graph;
}

SparseMatrix cell_coupling_pattern(const std::vector<MeshNodes>& meshes, Index node_count, int fields,
                                   const std::vector<Index>& free_index, Index free_count,
                                   const std::vector<char>& kept_rows) {
  const NodeGraph graph = node_graph(meshes, node_count, true);
  // Column free_index[node * fields + g] holds the free dofs of the node's neighbours (with itself).
  // Free dofs are numbered in dof order, so the columns come in order, and so do the rows of each
  // (neighbours sorted, fields ascending). Two passes: the columns' sizes, then their rows.
  const auto for_each_row = [&](Index node, auto visit) {
    for (Index k = graph.start[node]; k < graph.start[node + 1]; ++k)
      for (int f = 0; f < fields; ++f) {
        const Index row = free_index[graph.neighbour[k] * fields + f];
        if (row >= 0 && (kept_rows.empty() || kept_rows[row])) visit(row);
      }
  };
  SparseMatrix pattern(free_count, free_count);
  int* column_start = pattern.outerIndexPtr();
  column_start[0] = 0;
  Index column = 0;
  for (Index node = 0; node < node_count; ++node) {
    int size = 0;
    for_each_row(node, [&](Index) { ++size; });
    for (int g = 0; g < fields; ++g)
      if (free_index[node * fields + g] >= 0) {
        column_start[column + 1] = column_start[column] + size;
        ++column;
      }
  }
  pattern.resizeNonZeros(column_start[free_count]);
  int* rows = pattern.innerIndexPtr();
  std::fill(pattern.valuePtr(), pattern.valuePtr() + pattern.nonZeros(), 0.0);
  column = 0;
  for (Index node = 0; node < node_count; ++node)
    for (int g = 0; g < fields; ++g)
      if (free_index[node * fields + g] >= 0) {
        int at = column_start[column++];
        for_each_row(node, [&](Index row) { rows[at++] = static_cast<int>(row); });
      }
  return pattern;
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
