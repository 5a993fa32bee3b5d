// Box/hull pairs by separating axes, and a sphere against a box/hull by its closest point.
#include <cmath>
#include <limits>

#include "moreau/collision/narrow_phase_parts.hpp"
#include "moreau/collision/point_query.hpp"

namespace moreau::narrow {

namespace {

Vec3 world_support(const Shape& s, const Pose& p, const Vec3& direction) {
  return p.to_world(s.polyhedron.vertices[s.polyhedron.support_vertex(p.orientation.conjugate() * direction)]);
}

// Deepest separation of `other` from each face plane of `self` (both posed).
FaceAxis best_face_axis(const Shape& self, const Pose& ps, const Shape& other, const Pose& po) {
  FaceAxis best;
  const ConvexPolyhedron& poly = self.polyhedron;
  for (Index f = 0; f < static_cast<Index>(poly.faces.size()); ++f) {
    const Vec3 n = ps.orientation * poly.face_normals[f];
    const Real offset = poly.face_offsets[f] + n.dot(ps.position);
    const Real s = n.dot(world_support(other, po, -n)) - offset;
    if (s > best.separation) best = {s, f};
  }
  return best;
}

Feature face_feature(const Shape& s, const Pose& p, Index f) {
  Feature out;
  const auto& face = s.polyhedron.faces[f];
  for (Index v : face)
    if (out.count < Feature::capacity) out.points[out.count++] = p.to_world(s.polyhedron.vertices[v]);
  out.is_face = true;
  out.face_normal = p.orientation * s.polyhedron.face_normals[f];
  return out;
}

// The face of `s` whose normal is most opposite to world direction n.
Index incident_face(const Shape& s, const Pose& p, const Vec3& n) {
  const Vec3 local = p.orientation.conjugate() * n;
  Index best = 0;
  Real best_dot = std::numeric_limits<Real>::infinity();
  const auto& normals = s.polyhedron.face_normals;
  for (Index f = 0; f < static_cast<Index>(normals.size()); ++f)
    if (normals[f].dot(local) < best_dot) best_dot = normals[f].dot(local), best = f;
  return best;
}

// The edge of `s` parallel to world direction d that is furthest along `axis`.
void support_edge(const Shape& s, const Pose& p, const Vec3& d, const Vec3& axis, Vec3& e0, Vec3& e1) {
  const Vec3 dl = p.orientation.conjugate() * d, al = p.orientation.conjugate() * axis;
  const ConvexPolyhedron& poly = s.polyhedron;
  Real best = -std::numeric_limits<Real>::infinity();
  for (const auto& e : poly.edges) {
    const Vec3 a = poly.vertices[e[0]], b = poly.vertices[e[1]];
    const Vec3 dir = (b - a).normalized();
    if (std::abs(dir.dot(dl)) < 1 - 1e-6) continue;
    const Real along = 0.5 * (a + b).dot(al);
    if (along > best) best = along, e0 = p.to_world(a), e1 = p.to_world(b);
  }
}

}  // namespace

void collide_polyhedra(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb, Real margin,
                       Candidates& out) {
  SeparatingAxes axes;
  axes.face_a = best_face_axis(a, pa, b, pb);
  if (axes.face_a.separation > margin) return;
  axes.face_b = best_face_axis(b, pb, a, pa);
  if (axes.face_b.separation > margin) return;

  // Edge-edge axes, oriented from A to B.
  const Vec3 ab = pb.position - pa.position;
  for (const Vec3& da_local : a.polyhedron.edge_directions) {
    const Vec3 da = pa.orientation * da_local;
    for (const Vec3& db_local : b.polyhedron.edge_directions) {
      const Vec3 db = pb.orientation * db_local;
      Vec3 axis = da.cross(db);
      const Real len = axis.norm();
      if (len < 1e-6) continue;
      axis /= len;
      if (axis.dot(ab) < 0) axis = -axis;
      const Real s = axis.dot(world_support(b, pb, -axis)) - axis.dot(world_support(a, pa, axis));
      if (s > margin) return;
      if (s > axes.edge_separation) axes.edge_separation = s, axes.edge_axis = axis, axes.edge_dir_a = da, axes.edge_dir_b = db;
    }
  }
  contacts_from_axes(a, pa, b, pb, margin, axes, out);
}

void contacts_from_axes(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb, Real margin,
                        const SeparatingAxes& axes, Candidates& out) {
  const FaceAxis& face_a = axes.face_a;
  const FaceAxis& face_b = axes.face_b;
  // Prefer faces (stable manifolds) unless an edge axis separates clearly more.
  const Real scale = std::min(a.bounding_radius(), b.bounding_radius());
  const Real face_separation = std::max(face_a.separation, face_b.separation);
  if (axes.edge_separation > face_separation + 1e-3 * scale) {
    Vec3 a0, a1, b0, b1, on_a, on_b;
    support_edge(a, pa, axes.edge_dir_a, axes.edge_axis, a0, a1);
    support_edge(b, pb, axes.edge_dir_b, -axes.edge_axis, b0, b1);
    closest_points_of_segments(a0, a1, b0, b1, on_a, on_b);
    out.normal = -axes.edge_axis;
    out.frame = NormalFrame::body_b;
    out.add({on_a, on_b, 0, 0, (on_a - on_b).dot(out.normal)});
    return;
  }
  // Between nearly equal face axes take B's: pairs are ordered by body index and colliders come
  // last, so a box on the ground keeps the ground's normal.
  if (face_a.separation > face_b.separation + 1e-3 * scale) {
    const Feature reference = face_feature(a, pa, face_a.face);
    const Feature incident = face_feature(b, pb, incident_face(b, pb, reference.face_normal));
    contacts_from_features(reference, incident, -reference.face_normal, margin, out, Reference::a);
  } else {
    const Feature reference = face_feature(b, pb, face_b.face);
    const Feature incident = face_feature(a, pa, incident_face(a, pa, reference.face_normal));
    contacts_from_features(incident, reference, reference.face_normal, margin, out, Reference::b);
  }
}

void collide_sphere_polyhedron(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb, Real margin,
                               Candidates& out) {
  const SurfacePoint near = nearest_polyhedron_point(b.polyhedron, pb.to_local(pa.position));
  const Real separation = near.distance - a.radius;
  if (separation > margin) return;
  out.normal = pb.orientation * near.normal;
  out.frame = NormalFrame::body_b;
  out.add({pa.position, pb.to_world(near.point), a.radius, 0, separation});
}

}  // namespace moreau::narrow
