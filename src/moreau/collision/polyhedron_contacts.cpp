// Box/hull pairs by separating axes, and a sphere or a capsule against a box/hull by the closest
// points of its core.
#include <cmath>
#include <limits>

#include "moreau/collision/narrow_phase_parts.hpp"
#include "moreau/collision/point_query.hpp"

namespace moreau::narrow {

namespace {

Vec3 world_support(const Shape& s, const Pose& p, const Vec3& direction) {
  return p.to_world(s.support(p.orientation.conjugate() * direction));
}

}  // namespace

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

namespace {

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

// The signed distance from B of the core point p0 + t (p1 - p0) is convex in t (B is convex), so
// golden-section search finds its minimum; the normal there is the contact's. Taking the
// polyhedron's own nearest point avoids the bias of a penetration search along the line between
// the centres, which tilted the normal of a short capsule lying over a box's edge towards the
// box's centre and pushed it sideways off the edge.
void collide_capsule_polyhedron(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb, Real margin,
                                Candidates& out) {
  const Vec3 axis = pa.orientation * Vec3(0, a.half_height, 0);
  const Vec3 p0 = pb.to_local(pa.position - axis), p1 = pb.to_local(pa.position + axis);  // B's frame
  const ConvexPolyhedron& poly = b.polyhedron;
  auto at = [&](Real t) { return Vec3(p0 + t * (p1 - p0)); };
  auto query = [&](Real t) { return nearest_polyhedron_point(poly, at(t)); };
  constexpr Real kGolden = 0.6180339887498949;
  Real lo = 0, hi = 1, x1 = hi - kGolden * (hi - lo), x2 = lo + kGolden * (hi - lo);
  Real f1 = query(x1).distance, f2 = query(x2).distance;
  for (int k = 0; k < 60 && hi - lo > 1e-9; ++k) {
    if (f1 <= f2) {
      hi = x2, x2 = x1, f2 = f1;
      x1 = hi - kGolden * (hi - lo), f1 = query(x1).distance;
    } else {
      lo = x1, x1 = x2, f1 = f2;
      x2 = lo + kGolden * (hi - lo), f2 = query(x2).distance;
    }
  }
  // The ends themselves may be the minimum (the search only approaches them).
  Real best_t = 0.5 * (lo + hi);
  SurfacePoint best = query(best_t);
  for (Real t : {0.0, 1.0})
    if (const SurfacePoint end = query(t); end.distance < best.distance) best = end, best_t = t;
  const Real separation = best.distance - a.radius;
  if (separation > margin) return;
  const Vec3 n = best.normal;
  out.normal = pb.orientation * n;
  out.frame = NormalFrame::body_b;
  auto add = [&](const Vec3& core, const SurfacePoint& near) {
    out.add({pb.to_world(core), pb.to_world(near.point), a.radius, 0, near.distance - a.radius});
  };
  add(at(best_t), best);
  // Towards each end, the farthest core point whose nearest point on B faces along n and lies
  // within the margin: the end itself, or the boundary found by bisection.
  constexpr Real kSameNormal = 0.999;
  auto faces_n = [&](const SurfacePoint& q) { return q.normal.dot(n) > kSameNormal && q.distance - a.radius <= margin; };
  const Real length = (p1 - p0).norm();
  for (Real end : {0.0, 1.0}) {
    Real inside = best_t, outside = end;
    SurfacePoint q = query(end);
    if (!faces_n(q)) {
      for (int k = 0; k < 40; ++k) {
        const Real mid = 0.5 * (inside + outside);
        (faces_n(query(mid)) ? inside : outside) = mid;
      }
      outside = inside;
      q = query(inside);
    }
    if (std::abs(outside - best_t) * length > 1e-6 * (1 + length)) add(at(outside), q);
  }
}

}  // namespace moreau::narrow
