#pragma once
// Round quad4 meshes for immersed-body tests: an annulus (a Couette gap, a ring) and a disc.
#include <cmath>

#include "moreau/fem/core/fem_mesh.hpp"

namespace moreau::test {

/// An annulus r_in <= r <= r_out of quad4 cells, `radial` by `around` (node (i, j) is
/// j (radial + 1) + i, i outward, j counter-clockwise), with boundaries "inner" and "outer".
inline FemMesh annulus_mesh(Real r_in, Real r_out, int radial, int around) {
  FemMesh mesh;
  mesh.dim = 2;
  mesh.element = ElementType::quad4;
  for (int j = 0; j < around; ++j)
    for (int i = 0; i <= radial; ++i) {
      const Real r = r_in + (r_out - r_in) * i / radial, angle = 2 * kPi * j / around;
      mesh.nodes.emplace_back(r * std::cos(angle), r * std::sin(angle), 0);
    }
  auto node = [&](int i, int j) { return static_cast<Index>((j % around) * (radial + 1) + i); };
  FemBoundary inner{"inner", {}}, outer{"outer", {}};
  for (int j = 0; j < around; ++j) {
    for (int i = 0; i < radial; ++i)
      for (Index n : {node(i, j), node(i + 1, j), node(i + 1, j + 1), node(i, j + 1)}) mesh.cells.push_back(n);
    inner.facets.insert(inner.facets.end(), {node(0, j + 1), node(0, j)});
    outer.facets.insert(outer.facets.end(), {node(radial, j), node(radial, j + 1)});
  }
  mesh.boundaries = {inner, outer};
  return mesh;
}

/// A disc of radius R about `centre` as an O-grid of quad4 cells: a square core of half-width R/2
/// with n x n cells, and `layers` rings of 4n cells blending its edge into the circle, its edge the
/// boundary "rim". The mesh is symmetric under the reflections in the axes and the diagonals
/// through the centre.
inline FemMesh disc_mesh(const Vec3& centre, Real R, int n, int layers) {
  const Real a = R / 2;
  FemMesh mesh = make_rectangle_mesh(Vec2(-a, -a), Vec2(a, a), {n, n}, ElementType::quad4);
  mesh.boundaries.clear();
  // The core's edge nodes, counter-clockwise from (-a, -a) (rectangle nodes are j (n + 1) + i).
  std::vector<Index> edge;
  for (int i = 0; i < n; ++i) edge.push_back(i);
  for (int j = 0; j < n; ++j) edge.push_back(j * (n + 1) + n);
  for (int i = n; i > 0; --i) edge.push_back(n * (n + 1) + i);
  for (int j = n; j > 0; --j) edge.push_back(j * (n + 1));
  const int around = static_cast<int>(edge.size());
  std::vector<Index> previous = edge;
  for (int l = 1; l <= layers; ++l) {
    const Real s = static_cast<Real>(l) / layers;
    std::vector<Index> ring;
    for (Index e : edge) {
      const Vec3 p = mesh.nodes[e];
      ring.push_back(static_cast<Index>(mesh.nodes.size()));
      mesh.nodes.push_back((1 - s) * p + s * R * p.normalized());
    }
    for (int j = 0; j < around; ++j)
      for (Index v : {previous[j], ring[j], ring[(j + 1) % around], previous[(j + 1) % around]}) mesh.cells.push_back(v);
    previous = ring;
  }
  FemBoundary rim{"rim", {}};
  for (int j = 0; j < around; ++j) rim.facets.insert(rim.facets.end(), {previous[j], previous[(j + 1) % around]});
  mesh.boundaries = {rim};
  for (Vec3& p : mesh.nodes) p += centre;
  return mesh;
}

}  // namespace moreau::test
