#include "moreau/collision/shape.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>

#include "moreau/collision/mesh_shape.hpp"

namespace moreau {

void ConvexPolyhedron::finish_topology() {
  face_normals.clear();
  face_offsets.clear();
  edges.clear();
  edge_directions.clear();
  std::map<std::pair<Index, Index>, bool> seen;
  for (const auto& face : faces) {
    // Newell's normal: robust for any planar polygon.
    Vec3 n = Vec3::Zero(), centroid = Vec3::Zero();
    for (size_t k = 0; k < face.size(); ++k) {
      const Vec3& a = vertices[face[k]];
      const Vec3& b = vertices[face[(k + 1) % face.size()]];
      n += a.cross(b);
      centroid += a;
    }
    n.normalize();
    centroid /= Real(face.size());
    face_normals.push_back(n);
    face_offsets.push_back(n.dot(centroid));
    for (size_t k = 0; k < face.size(); ++k) {
      Index a = face[k], b = face[(k + 1) % face.size()];
      if (a > b) std::swap(a, b);
      if (seen.emplace(std::make_pair(a, b), true).second) edges.push_back({a, b});
    }
  }
  for (const auto& e : edges) {
    const Vec3 d = (vertices[e[1]] - vertices[e[0]]).normalized();
    const bool parallel = std::any_of(edge_directions.begin(), edge_directions.end(),
                                      [&](const Vec3& u) { return std::abs(u.dot(d)) > 1 - 1e-9; });
    if (!parallel) edge_directions.push_back(d);
  }
}

Index ConvexPolyhedron::support_vertex(const Vec3& direction) const {
  Index best = 0;
  Real best_dot = -std::numeric_limits<Real>::infinity();
  for (Index v = 0; v < static_cast<Index>(vertices.size()); ++v) {
    const Real d = vertices[v].dot(direction);
    if (d > best_dot) best_dot = d, best = v;
  }
  return best;
}

Real Shape::bounding_radius() const {
  switch (type) {
    case ShapeType::sphere: return radius;
    case ShapeType::capsule: return radius + half_height;
    case ShapeType::cylinder: return std::hypot(radius, half_height);
    case ShapeType::box:
    case ShapeType::convex_hull: {
      Real r = 0;
      for (const Vec3& v : polyhedron.vertices) r = std::max(r, v.norm());
      return r;
    }
    case ShapeType::plane: return std::numeric_limits<Real>::infinity();
    case ShapeType::triangle_mesh: return std::max(mesh->lower.norm(), mesh->upper.norm());
  }
  return 0;
}

Vec3 Shape::support(const Vec3& d) const {
  switch (type) {
    case ShapeType::sphere: return radius * d.normalized();
    case ShapeType::capsule: return Vec3(0, d.y() >= 0 ? half_height : -half_height, 0) + radius * d.normalized();
    case ShapeType::cylinder: {
      const Vec2 radial(d.x(), d.z());
      const Real rn = radial.norm();
      const Vec2 rim = rn > 0 ? Vec2(radius * radial / rn) : Vec2::Zero();
      return Vec3(rim.x(), d.y() >= 0 ? half_height : -half_height, rim.y());
    }
    case ShapeType::box:
    case ShapeType::convex_hull: return polyhedron.vertices[polyhedron.support_vertex(d)];
    case ShapeType::plane:
    case ShapeType::triangle_mesh: break;
  }
  return Vec3::Zero();
}

Vec3 Shape::local_half_extents() const {
  switch (type) {
    case ShapeType::sphere: return Vec3::Constant(radius);
    case ShapeType::capsule: return Vec3(radius, radius + half_height, radius);
    case ShapeType::cylinder: return Vec3(radius, half_height, radius);
    case ShapeType::box: return half_extents;
    case ShapeType::convex_hull: {
      Vec3 e = Vec3::Zero();
      for (const Vec3& v : polyhedron.vertices) e = e.cwiseMax(v.cwiseAbs());
      return e;
    }
    case ShapeType::triangle_mesh: return mesh->lower.cwiseAbs().cwiseMax(mesh->upper.cwiseAbs());
    case ShapeType::plane: break;
  }
  return Vec3::Constant(std::numeric_limits<Real>::infinity());
}

Shape make_sphere(Real radius) {
  Shape s;
  s.type = ShapeType::sphere;
  s.radius = radius;
  return s;
}

Shape make_triangle_mesh(std::shared_ptr<const MeshShape> mesh) {
  Shape s;
  s.type = ShapeType::triangle_mesh;
  s.mesh = std::move(mesh);
  return s;
}

Shape make_box(const Vec3& e) {
  Shape s;
  s.type = ShapeType::box;
  s.half_extents = e;
  ConvexPolyhedron& p = s.polyhedron;
  for (int k = 0; k < 8; ++k)
    p.vertices.emplace_back((k & 1) ? e.x() : -e.x(), (k & 2) ? e.y() : -e.y(), (k & 4) ? e.z() : -e.z());
  // Vertex k has bit 0 = +x, bit 1 = +y, bit 2 = +z; faces counter-clockwise from outside.
  p.faces = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
  p.finish_topology();
  return s;
}

namespace {
// A round shape along its local y axis (capsule or cylinder).
Shape make_round(ShapeType type, Real radius, Real half_height) {
  Shape s;
  s.type = type;
  s.radius = radius;
  s.half_height = half_height;
  return s;
}
}  // namespace

Shape make_capsule(Real radius, Real half_height) { return make_round(ShapeType::capsule, radius, half_height); }

Shape make_cylinder(Real radius, Real half_height) { return make_round(ShapeType::cylinder, radius, half_height); }

Shape make_plane() {
  Shape s;
  s.type = ShapeType::plane;
  return s;
}

namespace {

// Second moment C = int x x^T dV of the tetrahedron (0, a, b, c):
// C = det[a b c] / 120 (a a^T + b b^T + c c^T + s s^T), s = a + b + c (the canonical tetrahedron
// has int x^2 = 1/60 and int xy = 1/120; an affine map carries it to any other).
MassProperties polyhedron_mass_properties(const ConvexPolyhedron& p) {
  MassProperties m;
  Mat3 second = Mat3::Zero();
  Vec3 first = Vec3::Zero();
  for (const auto& face : p.faces)
    for (size_t k = 1; k + 1 < face.size(); ++k) {
      const Vec3& a = p.vertices[face[0]];
      const Vec3& b = p.vertices[face[k]];
      const Vec3& c = p.vertices[face[k + 1]];
      const Real det = a.dot(b.cross(c));
      const Vec3 s = a + b + c;
      m.volume += det / 6;
      first += det / 24 * s;
      second += det / 120 * (a * a.transpose() + b * b.transpose() + c * c.transpose() + s * s.transpose());
    }
  m.center = first / m.volume;
  const Mat3 central = second - m.volume * m.center * m.center.transpose();
  m.inertia = central.trace() * Mat3::Identity() - central;
  return m;
}

}  // namespace

MassProperties mass_properties(const Shape& s) {
  MassProperties m;
  const Real r = s.radius, r2 = r * r, a = s.half_height;
  switch (s.type) {
    case ShapeType::sphere:
      m.volume = 4.0 / 3 * kPi * r2 * r;
      m.inertia = Mat3::Identity() * 0.4 * m.volume * r2;
      break;
    case ShapeType::box: {
      const Vec3 e = s.half_extents;
      m.volume = 8 * e.prod();
      m.inertia.diagonal() = m.volume / 3 * Vec3(e.y() * e.y() + e.z() * e.z(), e.x() * e.x() + e.z() * e.z(),
                                                 e.x() * e.x() + e.y() * e.y());
      break;
    }
    case ShapeType::cylinder: {
      m.volume = kPi * r2 * 2 * a;
      const Real across = m.volume * (3 * r2 + 4 * a * a) / 12;
      m.inertia.diagonal() = Vec3(across, m.volume * r2 / 2, across);
      break;
    }
    case ShapeType::capsule: {
      // Cylinder of length 2a plus two hemispheres (each of volume 2/3 pi r^3, centroid 3r/8 from
      // its flat face, own transverse inertia 83/320 m r^2 about its centroid).
      const Real cylinder = kPi * r2 * 2 * a, hemisphere = 2.0 / 3 * kPi * r2 * r;
      m.volume = cylinder + 2 * hemisphere;
      const Real offset = a + 3 * r / 8;
      const Real axial = cylinder * r2 / 2 + 2 * (0.4 * hemisphere * r2);
      const Real across = cylinder * (3 * r2 + 4 * a * a) / 12 +
                          2 * hemisphere * (83.0 / 320 * r2 + offset * offset);
      m.inertia.diagonal() = Vec3(across, axial, across);
      break;
    }
    case ShapeType::convex_hull: return polyhedron_mass_properties(s.polyhedron);
    case ShapeType::plane:
    case ShapeType::triangle_mesh: break;  // no mass: fixed and kinematic bodies only
  }
  return m;
}

Mat3 move_to_principal_frame(Shape& shape, MassProperties& props) {
  if (shape.type != ShapeType::convex_hull) return Mat3::Identity();
  Eigen::SelfAdjointEigenSolver<Mat3> eig(props.inertia);
  Mat3 R = eig.eigenvectors();
  if (R.determinant() < 0) R.col(2) = -R.col(2);
  for (Vec3& v : shape.polyhedron.vertices) v = R.transpose() * (v - props.center);
  shape.polyhedron.finish_topology();
  props.inertia = eig.eigenvalues().asDiagonal();
  return R;
}

}  // namespace moreau
