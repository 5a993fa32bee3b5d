#include "moreau/collision/point_query.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "moreau/collision/mesh_shape.hpp"
#include "moreau/collision/narrow_phase_parts.hpp"

namespace moreau {

namespace {

// A round core (a point, or the segment |y| <= H of the local y axis) swept by radius R.
SurfacePoint nearest_round_point(Real half_height, Real radius, const Vec3& p) {
  const Vec3 core(0, std::clamp(p.y(), -half_height, half_height), 0);
  const Vec3 r = p - core;
  const Real len = r.norm();
  // On the core itself every direction is as near; take one across the segment.
  const Vec3 n = len > 0 ? Vec3(r / len) : Vec3::UnitX();
  return {len - radius, n, core + radius * n};
}

SurfacePoint nearest_box_point(const Vec3& h, const Vec3& p) {
  const Vec3 q = p.cwiseAbs() - h;
  if ((q.array() > 0).any()) {
    const Vec3 clamped = p.cwiseMax(-h).cwiseMin(h);
    const Vec3 r = p - clamped;
    const Real len = r.norm();
    return {len, r / len, clamped};
  }
  int axis = 0;
  q.maxCoeff(&axis);
  const Real side = p[axis] >= 0 ? 1 : -1;
  Vec3 n = Vec3::Zero(), point = p;
  n[axis] = side;
  point[axis] = side * h[axis];
  return {q[axis], n, point};
}

SurfacePoint nearest_cylinder_point(Real half_height, Real radius, const Vec3& p) {
  const Real rho = std::hypot(p.x(), p.z());
  const Vec3 radial = rho > 0 ? Vec3(p.x() / rho, 0, p.z() / rho) : Vec3::UnitX();
  const Real dr = rho - radius, dy = std::abs(p.y()) - half_height;
  const Real side = p.y() >= 0 ? 1 : -1;
  const Vec3 axial(0, side, 0);
  if (dr > 0 && dy > 0) {  // beyond the rim
    const Vec3 rim = radius * radial + half_height * axial;
    const Vec3 r = p - rim;
    const Real len = r.norm();
    return {len, r / len, rim};
  }
  if (dr > dy) return {dr, radial, Vec3(radius * radial.x(), p.y(), radius * radial.z())};
  return {dy, axial, Vec3(p.x(), side * half_height, p.z())};
}

}  // namespace

SurfacePoint nearest_polyhedron_point(const ConvexPolyhedron& poly, const Vec3& p) {
  const Index faces = static_cast<Index>(poly.faces.size());
  // Signed distances to the face planes; inside when all are <= 0.
  Real max_distance = -std::numeric_limits<Real>::infinity();
  Index max_face = 0;
  for (Index f = 0; f < faces; ++f) {
    const Real d = poly.face_normals[f].dot(p) - poly.face_offsets[f];
    if (d > max_distance) max_distance = d, max_face = f;
  }
  if (max_distance <= 0) {
    const Vec3& n = poly.face_normals[max_face];
    return {max_distance, n, p - max_distance * n};
  }
  // Outside: the nearest point is inside a face with positive distance, or on an edge.
  SurfacePoint best{std::numeric_limits<Real>::infinity(), Vec3::UnitY(), p};
  for (Index f = 0; f < faces; ++f) {
    const Vec3& n = poly.face_normals[f];
    const Real d = n.dot(p) - poly.face_offsets[f];
    if (d <= 0 || d >= best.distance) continue;
    const Vec3 q = p - d * n;
    const auto& face = poly.faces[f];
    bool inside = true;
    for (size_t k = 0; k < face.size() && inside; ++k) {
      const Vec3& v0 = poly.vertices[face[k]];
      const Vec3& v1 = poly.vertices[face[(k + 1) % face.size()]];
      inside = (v1 - v0).cross(q - v0).dot(n) >= 0;
    }
    if (inside) best = {d, n, q};
  }
  for (const auto& e : poly.edges) {
    Vec3 on_edge, on_p;
    narrow::closest_points_of_segments(poly.vertices[e[0]], poly.vertices[e[1]], p, p, on_edge, on_p);
    const Real d = (p - on_edge).norm();
    if (d < best.distance) best = {d, d > 0 ? Vec3((p - on_edge) / d) : poly.face_normals[max_face], on_edge};
  }
  // A point on an edge or a vertex, up to round-off (max_distance ~ 1e-17): the nearest face plane
  // gives the same point with a well-defined normal.
  if (best.distance <= max_distance) {
    const Vec3& n = poly.face_normals[max_face];
    return {max_distance, n, p - max_distance * n};
  }
  return best;
}

SurfacePoint nearest_surface_point(const Shape& shape, const Vec3& p) {
  switch (shape.type) {
    case ShapeType::sphere: return nearest_round_point(0, shape.radius, p);
    case ShapeType::capsule: return nearest_round_point(shape.half_height, shape.radius, p);
    case ShapeType::box: return nearest_box_point(shape.half_extents, p);
    case ShapeType::cylinder: return nearest_cylinder_point(shape.half_height, shape.radius, p);
    case ShapeType::convex_hull: return nearest_polyhedron_point(shape.polyhedron, p);
    case ShapeType::plane: return {p.y(), Vec3::UnitY(), Vec3(p.x(), 0, p.z())};
    case ShapeType::triangle_mesh: return nearest_mesh_point(*shape.mesh, p);
  }
  return {};
}

}  // namespace moreau
