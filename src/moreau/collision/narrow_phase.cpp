#include "moreau/collision/narrow_phase.hpp"

#include <algorithm>
#include <cmath>

#include "moreau/collision/mesh_shape.hpp"
#include "moreau/collision/narrow_phase_parts.hpp"

namespace moreau {

namespace narrow {

void closest_points_of_segments(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1, Vec3& on_p,
                                Vec3& on_q) {
  // Minimise |p0 + s d1 - q0 - t d2|^2 over s, t in [0, 1] (Ericson, Real-Time Collision
  // Detection, sec. 5.1.9).
  const Vec3 d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
  const Real a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  constexpr Real tiny = 1e-24;
  Real s = 0, t = 0;
  if (a <= tiny && e <= tiny) {
  } else if (a <= tiny) {
    t = std::clamp(f / e, Real(0), Real(1));
  } else {
    const Real c = d1.dot(r);
    if (e <= tiny) {
      s = std::clamp(-c / a, Real(0), Real(1));
    } else {
      const Real b = d1.dot(d2), denom = a * e - b * b;
      s = denom > tiny * a * e ? std::clamp((b * f - c * e) / denom, Real(0), Real(1)) : 0;
      t = (b * s + f) / e;
      if (t < 0) {
        t = 0;
        s = std::clamp(-c / a, Real(0), Real(1));
      } else if (t > 1) {
        t = 1;
        s = std::clamp((b - c) / a, Real(0), Real(1));
      }
    }
  }
  on_p = p0 + s * d1;
  on_q = q0 + t * d2;
}

ContactManifold reduce_to_manifold(const Candidates& c, const Pose& pa, const Pose& pb) {
  ContactManifold m;
  m.frame = c.frame;
  if (c.count == 0) return m;
  std::array<int, 4> keep{};
  int kept = 0;
  if (c.count <= 4) {
    for (int i = 0; i < c.count; ++i) keep[kept++] = i;
  } else {
    // Deepest point; the point furthest from it; the one making the largest triangle; the one
    // adding the most area outside that triangle.
    auto position = [&](int i) { return c.items[i].core_b; };
    int first = 0;
    for (int i = 1; i < c.count; ++i)
      if (c.items[i].separation < c.items[first].separation) first = i;
    int second = first;
    Real best = -1;
    for (int i = 0; i < c.count; ++i) {
      const Real d = (position(i) - position(first)).squaredNorm();
      if (d > best) best = d, second = i;
    }
    int third = first;
    best = -1;
    for (int i = 0; i < c.count; ++i) {
      const Real area = (position(i) - position(first)).cross(position(i) - position(second)).dot(c.normal);
      if (std::abs(area) > best) best = std::abs(area), third = i;
    }
    const Real orientation = (position(second) - position(first)).cross(position(third) - position(first)).dot(c.normal);
    int fourth = first;
    best = 0;
    for (int i = 0; i < c.count; ++i) {
      // Area added outside each edge of the triangle (negative signed area relative to its winding).
      const std::array<int, 3> tri{first, second, third};
      for (int k = 0; k < 3; ++k) {
        const Vec3 u = position(tri[(k + 1) % 3]) - position(tri[k]), v = position(i) - position(tri[k]);
        const Real outside = -u.cross(v).dot(c.normal) * (orientation >= 0 ? 1 : -1);
        if (outside > best) best = outside, fourth = i;
      }
    }
    keep = {first, second, third, fourth};
    kept = 4;
    std::sort(keep.begin(), keep.end());
    kept = static_cast<int>(std::unique(keep.begin(), keep.end()) - keep.begin());
  }
  const Vec3 n_local = c.frame == NormalFrame::body_a   ? Vec3(pa.orientation.conjugate() * c.normal)
                       : c.frame == NormalFrame::body_b ? Vec3(pb.orientation.conjugate() * c.normal)
                                                        : c.normal;
  for (int k = 0; k < kept; ++k) {
    const Candidate& cand = c.items[keep[k]];
    ContactGeometry& g = m.points[m.count++];
    g.core_a = pa.to_local(cand.core_a);
    g.core_b = pb.to_local(cand.core_b);
    g.radius_a = cand.radius_a;
    g.radius_b = cand.radius_b;
    g.normal = n_local;
    g.on_lines = cand.on_lines && c.frame == NormalFrame::cores;
    if (g.on_lines) {
      for (int e = 0; e < 2; ++e) {
        g.line_a[e] = pa.to_local(cand.line_a[e]);
        g.line_b[e] = pb.to_local(cand.line_b[e]);
      }
      // Judged once, here: judged again at every pose, segments turning out of line within a step
      // would send a manifold's points to one closest pair.
      const Vec3 da = cand.line_a[1] - cand.line_a[0], db = cand.line_b[1] - cand.line_b[0];
      g.parallel_lines = narrow::lie_along(da, db);
    }
  }
  return m;
}

namespace {

// The core of a round shape: a point (sphere) or a segment (capsule), in world space.
struct Core {
  Vec3 p0, p1;
  Real radius;
};

Core round_core(const Shape& s, const Pose& pose) {
  const Vec3 axis = pose.orientation * Vec3(0, s.half_height, 0);
  return {pose.position - axis, pose.position + axis, s.radius};
}

void collide_round(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb, Real margin,
                   Candidates& out) {
  const Core ca = round_core(a, pa), cb = round_core(b, pb);
  Vec3 on_a, on_b;
  closest_points_of_segments(ca.p0, ca.p1, cb.p0, cb.p1, on_a, on_b);
  const Vec3 d = on_a - on_b;
  const Real dist = d.norm();
  const Real separation = dist - ca.radius - cb.radius;
  if (separation > margin) return;
  out.normal = dist > 1e-12 ? Vec3(d / dist) : Vec3(pa.orientation * Vec3::UnitY());
  out.frame = NormalFrame::cores;
  out.add(Candidate{on_a, on_b, ca.radius, cb.radius, separation}.along(ca.p0, ca.p1, cb.p0, cb.p1));
  // Two parallel capsules lie along each other: add the other end of the overlap so they do not
  // pivot about one point.
  const Vec3 da = ca.p1 - ca.p0, db = cb.p1 - cb.p0;
  if (lie_along(da, db)) {
    for (const Vec3& end : {ca.p0, ca.p1}) {
      Vec3 e_a, e_b;
      closest_points_of_segments(end, end, cb.p0, cb.p1, e_a, e_b);
      if ((e_a - on_a).norm() < 1e-6 * (1 + da.norm())) continue;
      const Real s = (e_a - e_b).dot(out.normal) - ca.radius - cb.radius;
      if (s <= margin && ((e_a - e_b) - (e_a - e_b).dot(out.normal) * out.normal).norm() < 1e-6 + 1e-3 * da.norm())
        out.add(Candidate{e_a, e_b, ca.radius, cb.radius, s}.along(ca.p0, ca.p1, cb.p0, cb.p1));
    }
  }
}

// A shape against the half-space y <= 0 of the plane's frame (B is the plane).
void collide_plane(const Shape& a, const Pose& pa, const Pose& plane, Real margin, Candidates& out) {
  const Vec3 n = plane.orientation * Vec3::UnitY();
  const Real offset = n.dot(plane.position);
  out.normal = n;
  out.frame = NormalFrame::body_b;
  auto add_point = [&](const Vec3& core, Real radius) {
    const Real s = n.dot(core) - offset - radius;
    if (s <= margin) out.add({core, core - (s + radius) * n, radius, 0, s});
  };
  switch (a.type) {
    case ShapeType::sphere: add_point(pa.position, a.radius); break;
    case ShapeType::capsule: {
      const Core c = round_core(a, pa);
      add_point(c.p0, c.radius);
      add_point(c.p1, c.radius);
      break;
    }
    case ShapeType::box:
    case ShapeType::convex_hull:
      for (const Vec3& v : a.polyhedron.vertices) add_point(pa.to_world(v), 0);
      break;
    case ShapeType::cylinder: {
      const narrow::Feature f = support_feature(a, pa, -n);
      for (int k = 0; k < f.count; ++k) add_point(f.points[k], f.radius);
      break;
    }
    case ShapeType::plane:
    case ShapeType::triangle_mesh: break;  // both fixed or kinematic: never a pair
  }
}

}  // namespace
}  // namespace narrow

void swap_sides(ContactManifold& m) {
  for (int k = 0; k < m.count; ++k) {
    ContactGeometry& g = m.points[k];
    std::swap(g.core_a, g.core_b);
    std::swap(g.radius_a, g.radius_b);
    std::swap(g.line_a, g.line_b);
    g.normal = -g.normal;
  }
  if (m.frame == NormalFrame::body_a) m.frame = NormalFrame::body_b;
  else if (m.frame == NormalFrame::body_b) m.frame = NormalFrame::body_a;
}

ContactManifold collide_shapes(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb, Real margin) {
  using namespace narrow;
  // Put the plane, the polyhedron or the non-round shape second; remember to swap back.
  auto rank = [](const Shape& s) {
    switch (s.type) {
      case ShapeType::sphere: return 0;
      case ShapeType::capsule: return 1;
      case ShapeType::cylinder: return 2;
      case ShapeType::box:
      case ShapeType::convex_hull: return 3;
      case ShapeType::plane:
      case ShapeType::triangle_mesh: return 4;
    }
    return 0;
  };
  // Meshes give one manifold per triangle: collide_with_mesh.
  if (a.type == ShapeType::triangle_mesh || b.type == ShapeType::triangle_mesh) return {};
  if (rank(a) > rank(b)) {
    ContactManifold m = collide_shapes(b, pb, a, pa, margin);
    swap_sides(m);
    return m;
  }
  Candidates c;
  if (b.type == ShapeType::plane) {
    if (a.type != ShapeType::plane) collide_plane(a, pa, pb, margin, c);
  } else if (a.is_round() && b.is_round()) {
    collide_round(a, pa, b, pb, margin, c);
  } else if (a.type == ShapeType::box && b.type == ShapeType::box) {
    collide_boxes(a, pa, b, pb, margin, c);
  } else if (a.is_polyhedron() && b.is_polyhedron()) {
    collide_polyhedra(a, pa, b, pb, margin, c);
  } else if (a.type == ShapeType::sphere && b.is_polyhedron()) {
    collide_sphere_polyhedron(a, pa, b, pb, margin, c);
  } else if (a.type == ShapeType::capsule && b.is_polyhedron()) {
    collide_capsule_polyhedron(a, pa, b, pb, margin, c);
  } else {
    collide_convex_mpr(a, pa, b, pb, margin, c);
  }
  return reduce_to_manifold(c, pa, pb);
}

void collide_with_mesh(const Shape& convex, const Pose& pose, const Shape& mesh, const Pose& mesh_pose,
                       Real margin, std::vector<ContactManifold>& out) {
  const MeshShape& m = *mesh.mesh;
  if (convex.type == ShapeType::plane || convex.type == ShapeType::triangle_mesh) return;
  // The convex shape's bounds in the mesh frame, grown by the margin.
  const Quat relative = mesh_pose.orientation.conjugate() * pose.orientation;
  const Vec3 center = mesh_pose.to_local(pose.position);
  const Vec3 half = relative.toRotationMatrix().cwiseAbs() * convex.local_half_extents() + Vec3::Constant(margin);
  thread_local std::vector<Index> near;
  m.triangles_near(center - half, center + half, near);
  constexpr Real kMinFrontCosine = 0.5;  // contacts within 60 degrees of the front normal
  constexpr Real kSameNormalCosine = 0.999;  // manifolds merged when their normals agree to 2.6 degrees
  // Per triangle, then merged by normal: a face resting across the seams of a flat region is one
  // manifold of up to four points, as on a single solid (separate manifolds per triangle each
  // held a share of the friction and let a sliding box run 22 % too far).
  thread_local std::vector<narrow::Candidates> groups;
  groups.clear();
  for (Index t : near) {
    const ContactManifold cm = collide_shapes(convex, pose, m.prisms[t], mesh_pose, margin);
    if (cm.count == 0) continue;
    const Vec3 front = mesh_pose.orientation * m.normals[t];
    const Vec3 n = contact_normal(cm.frame, cm.points[0], pose, mesh_pose);
    if (n.dot(front) < kMinFrontCosine) continue;
    narrow::Candidates* group = nullptr;
    for (narrow::Candidates& g : groups)
      if (g.normal.dot(n) > kSameNormalCosine) group = &g;
    if (group == nullptr) {
      group = &groups.emplace_back();
      group->normal = n;
      group->frame = NormalFrame::body_b;
    }
    for (int k = 0; k < cm.count; ++k) {
      const ContactGeometry& g = cm.points[k];
      const Vec3 ca = pose.to_world(g.core_a), cb = mesh_pose.to_world(g.core_b);
      const Real separation = ((ca - g.radius_a * group->normal) - (cb + g.radius_b * group->normal)).dot(group->normal);
      // A point on a seam comes from both triangles: keep it once.
      bool seen = false;
      for (int i = 0; i < group->count && !seen; ++i) seen = (group->items[i].core_b - cb).squaredNorm() < 1e-18;
      if (!seen) group->add({ca, cb, g.radius_a, g.radius_b, separation});
    }
  }
  for (const narrow::Candidates& g : groups) out.push_back(narrow::reduce_to_manifold(g, pose, mesh_pose));
}

CorePoints contact_cores(NormalFrame frame, const ContactGeometry& c, const Pose& pa, const Pose& pb) {
  CorePoints cores{pa.to_world(c.core_a), pb.to_world(c.core_b)};
  if (frame != NormalFrame::cores || !c.on_lines) return cores;
  const Vec3 a0 = pa.to_world(c.line_a[0]), a1 = pa.to_world(c.line_a[1]);
  const Vec3 b0 = pb.to_world(c.line_b[0]), b1 = pb.to_world(c.line_b[1]);
  if (!c.parallel_lines) {
    narrow::closest_points_of_segments(a0, a1, b0, b1, cores.a, cores.b);
  } else {
    // Segments along each other have no single closest pair: each point of the manifold keeps its
    // place on A and finds the point of B opposite it.
    Vec3 unused;
    narrow::closest_points_of_segments(cores.a, cores.a, b0, b1, unused, cores.b);
  }
  return cores;
}

Vec3 contact_normal(NormalFrame frame, const ContactGeometry& c, const Pose& pa, const Pose& pb,
                    const CorePoints& cores) {
  switch (frame) {
    case NormalFrame::body_a: return pa.orientation * c.normal;
    case NormalFrame::body_b: return pb.orientation * c.normal;
    case NormalFrame::cores: {
      const Vec3 d = cores.a - cores.b;
      const Real len = d.norm();
      return len > 1e-12 ? Vec3(d / len) : c.normal;
    }
  }
  return c.normal;
}

}  // namespace moreau
