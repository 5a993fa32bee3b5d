#include "moreau/collision/mesh_shape.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "moreau/collision/point_query.hpp"
#include "moreau/collision/shape.hpp"

namespace moreau {

namespace {

// Closest point of triangle (a, b, c) to p, by the Voronoi regions of its vertices, edges and face
// (Ericson, Real-Time Collision Detection, sec. 5.1.5).
Vec3 closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const Real d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Vec3 bp = p - b;
  const Real d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const Real vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + d1 / (d1 - d3) * ab;
  const Vec3 cp = p - c;
  const Real d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const Real vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + d2 / (d2 - d6) * ac;
  const Real va = d3 * d6 - d5 * d4;
  if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) return b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b);
  const Real denom = 1 / (va + vb + vc);
  return a + ab * (vb * denom) + ac * (vc * denom);
}

}  // namespace

std::shared_ptr<const MeshShape> make_mesh_shape(const TriangleMesh& mesh, Real thickness) {
  auto shape = std::make_shared<MeshShape>();
  MeshShape& m = *shape;
  m.thickness = thickness;
  m.surface.vertices = mesh.vertices;
  const auto& X = mesh.vertices;
  Real edge_sum = 0;
  m.lower = Vec3::Constant(std::numeric_limits<Real>::infinity());
  m.upper = -m.lower;
  for (const auto& t : mesh.triangles) {
    const Vec3 n = (X[t[1]] - X[t[0]]).cross(X[t[2]] - X[t[0]]);
    const Real scale = std::max({(X[t[1]] - X[t[0]]).norm(), (X[t[2]] - X[t[0]]).norm(), (X[t[2]] - X[t[1]]).norm()});
    if (n.norm() <= 1e-12 * scale * scale) continue;  // degenerate
    const Vec3 unit = n.normalized();
    // The slab: the triangle and its copy `thickness` behind it, as a convex hull.
    std::vector<Vec3> corners;
    for (Index v : t) corners.push_back(X[v]);
    for (Index v : t) corners.push_back(X[v] - thickness * unit);
    Shape prism;
    prism.type = ShapeType::convex_hull;
    prism.polyhedron = convex_hull(corners);
    for (const Vec3& v : corners) m.lower = m.lower.cwiseMin(v), m.upper = m.upper.cwiseMax(v);
    m.surface.triangles.push_back(t);
    m.normals.push_back(unit);
    m.prisms.push_back(std::move(prism));
    edge_sum += scale;
  }
  const Index count = static_cast<Index>(m.surface.triangles.size());
  if (count == 0) throw std::invalid_argument("the mesh has no triangle with a non-zero area");

  // Grid: cells about the size of a triangle's longest edge, at most 64^3 of them.
  const Vec3 extent = (m.upper - m.lower).cwiseMax(Vec3::Constant(1e-9));
  m.cell = std::max(edge_sum / count, extent.maxCoeff() / 64);
  for (int a = 0; a < 3; ++a) m.cells[a] = std::max(1, static_cast<int>(std::ceil(extent[a] / m.cell)));
  const Index total = static_cast<Index>(m.cells.prod());
  std::vector<std::vector<Index>> lists(total);
  for (Index t = 0; t < count; ++t) {
    Vec3 lo = Vec3::Constant(std::numeric_limits<Real>::infinity()), hi = -lo;
    for (const Vec3& v : m.prisms[t].polyhedron.vertices) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
    Eigen::Vector3i c0, c1;
    m.cell_range(lo, hi, c0, c1);
    for (int i = c0.x(); i <= c1.x(); ++i)
      for (int j = c0.y(); j <= c1.y(); ++j)
        for (int k = c0.z(); k <= c1.z(); ++k) lists[(k * m.cells.y() + j) * m.cells.x() + i].push_back(t);
  }
  m.cell_begin.push_back(0);
  for (const auto& list : lists) {
    m.cell_triangles.insert(m.cell_triangles.end(), list.begin(), list.end());
    m.cell_begin.push_back(static_cast<Index>(m.cell_triangles.size()));
  }
  return shape;
}

void MeshShape::cell_range(const Vec3& lo, const Vec3& hi, Eigen::Vector3i& c0, Eigen::Vector3i& c1) const {
  for (int a = 0; a < 3; ++a) {
    c0[a] = std::clamp(static_cast<int>(std::floor((lo[a] - lower[a]) / cell)), 0, cells[a] - 1);
    c1[a] = std::clamp(static_cast<int>(std::floor((hi[a] - lower[a]) / cell)), 0, cells[a] - 1);
  }
}

void MeshShape::triangles_near(const Vec3& lo, const Vec3& hi, std::vector<Index>& out) const {
  out.clear();
  if ((lo.array() > upper.array()).any() || (hi.array() < lower.array()).any()) return;
  Eigen::Vector3i c0, c1;
  cell_range(lo, hi, c0, c1);
  for (int i = c0.x(); i <= c1.x(); ++i)
    for (int j = c0.y(); j <= c1.y(); ++j)
      for (int k = c0.z(); k <= c1.z(); ++k) {
        const Index c = (k * cells.y() + j) * cells.x() + i;
        out.insert(out.end(), cell_triangles.begin() + cell_begin[c], cell_triangles.begin() + cell_begin[c + 1]);
      }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
}

SurfacePoint nearest_mesh_point(const MeshShape& mesh, const Vec3& p) {
  thread_local std::vector<Index> near;
  mesh.triangles_near(p - Vec3::Constant(mesh.cell), p + Vec3::Constant(mesh.cell), near);
  SurfacePoint best{std::numeric_limits<Real>::infinity(), Vec3::UnitY(), p};
  Real best_unsigned = std::numeric_limits<Real>::infinity();
  const auto& X = mesh.surface.vertices;
  for (Index t : near) {
    const auto& tri = mesh.surface.triangles[t];
    const Vec3 c = closest_point_on_triangle(p, X[tri[0]], X[tri[1]], X[tri[2]]);
    const Vec3 r = p - c;
    const Real d = r.norm();
    if (d >= best_unsigned) continue;
    const Vec3& n = mesh.normals[t];
    const Real along = r.dot(n);
    if (along >= 0) {
      best = {d, d > 1e-12 ? Vec3(r / d) : n, c};
    } else {
      if (-along > mesh.thickness) continue;  // beyond the slab: the far side of a thin wall
      best = {-d, n, c};
    }
    best_unsigned = d;
  }
  return best;
}

}  // namespace moreau
