#include "moreau/geometry/meshes.hpp"

#include <algorithm>
#include <map>

namespace moreau {

namespace {
std::array<Index, 2> sorted_edge(Index a, Index b) { return a < b ? std::array{a, b} : std::array{b, a}; }

void sort_unique(std::vector<std::array<Index, 2>>& edges) {
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
}
}  // namespace

std::vector<std::array<Index, 2>> triangle_edges(const std::vector<std::array<Index, 3>>& triangles) {
  std::vector<std::array<Index, 2>> edges;
  edges.reserve(triangles.size() * 3);
  for (const auto& t : triangles)
    for (int k = 0; k < 3; ++k) edges.push_back(sorted_edge(t[k], t[(k + 1) % 3]));
  sort_unique(edges);
  return edges;
}

std::vector<std::array<Index, 2>> tet_edges(const std::vector<std::array<Index, 4>>& tets) {
  std::vector<std::array<Index, 2>> edges;
  edges.reserve(tets.size() * 6);
  for (const auto& t : tets)
    for (int a = 0; a < 4; ++a)
      for (int b = a + 1; b < 4; ++b) edges.push_back(sorted_edge(t[a], t[b]));
  sort_unique(edges);
  return edges;
}

std::vector<Hinge> triangle_hinges(const std::vector<std::array<Index, 3>>& triangles) {
  // For every undirected edge remember (triangle, local edge) of each incidence.
  std::map<std::array<Index, 2>, std::vector<std::pair<Index, int>>> incidences;
  for (Index t = 0; t < static_cast<Index>(triangles.size()); ++t)
    for (int k = 0; k < 3; ++k)
      incidences[sorted_edge(triangles[t][k], triangles[t][(k + 1) % 3])].push_back({t, k});

  std::vector<Hinge> hinges;
  for (const auto& [edge, list] : incidences) {
    if (list.size() != 2) continue;
    const auto& ta = triangles[list[0].first];
    const auto& tb = triangles[list[1].first];
    const int ka = list[0].second, kb = list[1].second;
    Hinge h;
    h.e0 = ta[ka];
    h.e1 = ta[(ka + 1) % 3];
    h.o0 = ta[(ka + 2) % 3];
    h.o1 = tb[(kb + 2) % 3];
    hinges.push_back(h);
  }
  return hinges;
}

std::vector<std::array<Index, 3>> tet_boundary_faces(const TetMesh& mesh) {
  // Outward faces of a positively oriented tet (a, b, c, d).
  static constexpr int kFace[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  std::map<std::array<Index, 3>, std::pair<std::array<Index, 3>, int>> faces;
  for (const auto& t : mesh.tets) {
    for (const auto& f : kFace) {
      std::array<Index, 3> oriented{t[f[0]], t[f[1]], t[f[2]]};
      std::array<Index, 3> key = oriented;
      std::sort(key.begin(), key.end());
      auto [it, inserted] = faces.try_emplace(key, oriented, 0);
      it->second.second += 1;
    }
  }
  std::vector<std::array<Index, 3>> boundary;
  for (const auto& [key, value] : faces)
    if (value.second == 1) boundary.push_back(value.first);
  return boundary;
}

}  // namespace moreau
