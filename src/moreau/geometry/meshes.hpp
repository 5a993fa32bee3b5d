#pragma once
// Plain mesh containers shared by the generators, the readers and the model builder.
#include <array>
#include <vector>

#include "moreau/math/types.hpp"

namespace moreau {

/// A triangle surface. Triangles are counter-clockwise seen from the side their normal points to.
struct TriangleMesh {
  std::vector<Vec3> vertices;                  // m
  std::vector<std::array<Index, 3>> triangles;
};

/// A tetrahedral volume mesh. Every tetrahedron (a, b, c, d) is positively oriented:
/// det[b-a, c-a, d-a] > 0.
struct TetMesh {
  std::vector<Vec3> vertices;                  // m
  std::vector<std::array<Index, 4>> tets;
};

/// An edge shared by two triangles: the edge (e0, e1) and the vertices opposite it in each
/// triangle (o0 in the triangle where the edge runs e0 -> e1, o1 in the other).
struct Hinge {
  Index e0, e1, o0, o1;
};

/// Signed volume of the tetrahedron (a, b, c, d): det[b-a, c-a, d-a] / 6.
inline Real tet_signed_volume(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  return (b - a).cross(c - a).dot(d - a) / 6.0;
}

/// Unique undirected edges of a triangle list, sorted (lower index first) for determinism.
std::vector<std::array<Index, 2>> triangle_edges(const std::vector<std::array<Index, 3>>& triangles);

/// Unique undirected edges of a tetrahedron list, sorted.
std::vector<std::array<Index, 2>> tet_edges(const std::vector<std::array<Index, 4>>& tets);

/// Interior edges of a triangle surface with the two opposite vertices (the bending stencil).
/// Edges shared by more than two triangles (non-manifold) are skipped.
std::vector<Hinge> triangle_hinges(const std::vector<std::array<Index, 3>>& triangles);

/// The faces of a tet mesh that belong to exactly one tetrahedron, oriented outward.
std::vector<std::array<Index, 3>> tet_boundary_faces(const TetMesh& mesh);

}  // namespace moreau
