// Contact manifolds from supporting features: a reference face, an incident feature clipped
// against the reference face's side planes (Sutherland-Hodgman), and the separations of what is
// left. The normal of pairs without an analytic test comes from libccd's Minkowski portal
// refinement (Snethen, "XenoCollide", Game Programming Gems 7, 2008).
#include <ccd/ccd.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "moreau/collision/narrow_phase_parts.hpp"

namespace moreau::narrow {

namespace {

// Cosine above which a face counts as facing a direction (about 25 degrees).
constexpr Real kFaceAlignment = 0.9;
// Cylinder caps are represented by this many rim points in a manifold.
constexpr int kCapPoints = 8;
// |cosine| between a direction and the axis of a capsule or cylinder below which its side (the
// whole core) is the feature (about 3 degrees from square).
constexpr Real kSideAlignment = 0.05;
// Share of the radii the cores must stay apart for their line to be the normal.
constexpr Real kRoundNormalGap = 0.01;
// m: how much deeper than MPR's direction a polyhedron's face axis may be and still be taken.
constexpr Real kFaceAxisSlack = 1e-9;

}  // namespace

Feature support_feature(const Shape& s, const Pose& pose, const Vec3& direction) {
  Feature f;
  const Vec3 d = pose.orientation.conjugate() * direction.normalized();
  auto add = [&](const Vec3& local) { f.points[f.count++] = pose.to_world(local); };
  switch (s.type) {
    case ShapeType::sphere:
      add(Vec3::Zero());
      f.radius = s.radius;
      break;
    case ShapeType::capsule:
      f.radius = s.radius;
      if (std::abs(d.y()) < kSideAlignment) {
        add(Vec3(0, -s.half_height, 0));
        add(Vec3(0, s.half_height, 0));
      } else {
        add(Vec3(0, d.y() > 0 ? s.half_height : -s.half_height, 0));
      }
      break;
    case ShapeType::cylinder: {
      const Real cap_y = d.y() > 0 ? s.half_height : -s.half_height;
      const Vec2 radial(d.x(), d.z());
      const Real rn = radial.norm();
      if (std::abs(d.y()) > kFaceAlignment) {
        // The cap: counter-clockwise seen from outside.
        for (int k = 0; k < kCapPoints; ++k) {
          const Real angle = 2 * kPi * k / kCapPoints * (cap_y > 0 ? -1 : 1);
          add(Vec3(s.radius * std::cos(angle), cap_y, s.radius * std::sin(angle)));
        }
        f.is_face = true;
        f.face_normal = pose.orientation * Vec3(0, cap_y > 0 ? 1 : -1, 0);
      } else if (std::abs(d.y()) < kSideAlignment) {
        // The side: the axis swept by the radius, as a capsule's core. A contact anchored on the
        // axis stays under the surface while the cylinder turns about it; one anchored on the rim
        // would be carried round with the material and lift off (a rolling wheel sank and sped up).
        add(Vec3(0, -s.half_height, 0));
        add(Vec3(0, s.half_height, 0));
        f.radius = s.radius;
      } else {
        // The rim where side and cap meet: an edge.
        const Vec2 rim = s.radius * radial / rn;
        add(Vec3(rim.x(), cap_y, rim.y()));
      }
      break;
    }
    case ShapeType::box:
    case ShapeType::convex_hull: {
      const ConvexPolyhedron& poly = s.polyhedron;
      Index best = 0;
      Real best_dot = -2;
      for (Index k = 0; k < static_cast<Index>(poly.face_normals.size()); ++k)
        if (poly.face_normals[k].dot(d) > best_dot) best_dot = poly.face_normals[k].dot(d), best = k;
      if (best_dot > kFaceAlignment) {
        for (Index v : poly.faces[best])
          if (f.count < Feature::capacity) add(poly.vertices[v]);
        f.is_face = true;
        f.face_normal = pose.orientation * poly.face_normals[best];
      } else {
        add(poly.vertices[poly.support_vertex(d)]);
      }
      break;
    }
    case ShapeType::plane:
    case ShapeType::triangle_mesh: break;
  }
  return f;
}

namespace {

// Keeps the part of the point list (a polygon, a segment or a point) on the inner side of the
// plane {x : m . x <= offset}.
int clip(const std::array<Vec3, 64>& in, int count, const Vec3& m, Real offset, std::array<Vec3, 64>& out) {
  int n = 0;
  if (count == 1) {
    if (m.dot(in[0]) <= offset) out[n++] = in[0];
    return n;
  }
  const int edges = count == 2 ? 1 : count;
  if (count == 2) {
    const Real d0 = m.dot(in[0]) - offset, d1 = m.dot(in[1]) - offset;
    if (d0 <= 0) out[n++] = in[0];
    if ((d0 < 0) != (d1 < 0) && d0 != d1) out[n++] = in[0] + d0 / (d0 - d1) * (in[1] - in[0]);
    if (d1 <= 0) out[n++] = in[1];
    return n;
  }
  for (int k = 0; k < edges; ++k) {
    const Vec3& p = in[k];
    const Vec3& q = in[(k + 1) % count];
    const Real dp = m.dot(p) - offset, dq = m.dot(q) - offset;
    if (dp <= 0 && n < 64) out[n++] = p;
    if ((dp < 0) != (dq < 0) && dp != dq && n < 64) out[n++] = p + dp / (dp - dq) * (q - p);
  }
  return n;
}

}  // namespace

void contacts_from_features(const Feature& fa, const Feature& fb, const Vec3& n, Real margin, Candidates& out,
                            Reference reference) {
  if (reference == Reference::automatic) {
    const Real align_a = fa.is_face ? fa.face_normal.dot(-n) : -2;
    const Real align_b = fb.is_face ? fb.face_normal.dot(n) : -2;
    if (align_a > 0 || align_b > 0) reference = align_a > align_b ? Reference::a : Reference::b;
  }
  if (reference == Reference::automatic) {
    // Neither side has a face: points or edges meet; their closest points are the contact.
    Vec3 on_a, on_b;
    closest_points_of_segments(fa.points[0], fa.points[fa.count - 1], fb.points[0], fb.points[fb.count - 1], on_a,
                               on_b);
    out.normal = n;
    out.frame = NormalFrame::body_b;
    // A rounded feature (a capsule's or a cylinder's side, a sphere) touches along the line of
    // the closest points: that normal follows both bodies as they turn or roll.
    const Real gap = (on_a - on_b).norm();
    if ((fa.radius > 0 || fb.radius > 0) && gap > kRoundNormalGap * (fa.radius + fb.radius)) {
      out.normal = (on_a - on_b) / gap;
      out.frame = NormalFrame::cores;
    }
    const Real s = (on_a - on_b).dot(out.normal) - fa.radius - fb.radius;
    if (s <= margin)
      out.add(Candidate{on_a, on_b, fa.radius, fb.radius, s}.along(fa.points[0], fa.points[fa.count - 1], fb.points[0],
                                                                    fb.points[fb.count - 1]));
    return;
  }
  const bool a_is_reference = reference == Reference::a;
  const Feature& ref = a_is_reference ? fa : fb;
  const Feature& inc = a_is_reference ? fb : fa;
  // Outward normal of the reference face, towards the incident body.
  const Vec3 face_n = ref.face_normal;
  const Real face_offset = face_n.dot(ref.points[0]);

  std::array<Vec3, 64> poly{}, next{};
  int count = inc.count;
  for (int k = 0; k < count; ++k) poly[k] = inc.points[k];
  for (int k = 0; k < ref.count && count > 0; ++k) {
    const Vec3& v0 = ref.points[k];
    const Vec3& v1 = ref.points[(k + 1) % ref.count];
    const Vec3 side = (v1 - v0).cross(face_n);
    const Real len = side.norm();
    if (len <= 0) continue;
    count = clip(poly, count, side / len, side.dot(v0) / len, next);
    std::swap(poly, next);
  }
  out.normal = a_is_reference ? Vec3(-face_n) : face_n;
  out.frame = a_is_reference ? NormalFrame::body_a : NormalFrame::body_b;
  for (int k = 0; k < count; ++k) {
    // The incident surface point faces the reference: its core moved by its radius along -face_n.
    const Vec3 surface = poly[k] - inc.radius * face_n;
    const Real s = face_n.dot(surface) - face_offset;
    if (s > margin) continue;
    const Vec3 on_face = surface - s * face_n;
    if (a_is_reference) out.add({on_face, poly[k], 0, inc.radius, s});
    else out.add({poly[k], on_face, inc.radius, 0, s});
  }
}

namespace {

struct MprShape {
  const Shape* shape;
  const Pose* pose;
  Real inflate;  // m, grows the shape so that near misses within the margin overlap
};

void mpr_support(const void* object, const ccd_vec3_t* dir, ccd_vec3_t* out) {
  const auto* s = static_cast<const MprShape*>(object);
  const Vec3 d(dir->v[0], dir->v[1], dir->v[2]);
  const Vec3 p = s->pose->to_world(s->shape->support(s->pose->orientation.conjugate() * d)) +
                 s->inflate * d.normalized();
  ccdVec3Set(out, p.x(), p.y(), p.z());
}

void mpr_center(const void* object, ccd_vec3_t* out) {
  const auto* s = static_cast<const MprShape*>(object);
  ccdVec3Set(out, s->pose->position.x(), s->pose->position.y(), s->pose->position.z());
}

}  // namespace

void collide_convex_mpr(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb, Real margin,
                        Candidates& out) {
  const MprShape sa{&a, &pa, 0.5 * margin}, sb{&b, &pb, 0.5 * margin};
  ccd_t ccd;
  CCD_INIT(&ccd);
  ccd.support1 = mpr_support;
  ccd.support2 = mpr_support;
  ccd.center1 = mpr_center;
  ccd.center2 = mpr_center;
  ccd.mpr_tolerance = 1e-9;
  ccd.max_iterations = 200;
  ccd_real_t depth;
  ccd_vec3_t dir, pos;
  if (ccdMPRPenetration(&sa, &sb, &ccd, &depth, &dir, &pos) != 0) return;
  // libccd's direction moves the second object out of the first: it points from A to B.
  Vec3 n(-dir.v[0], -dir.v[1], -dir.v[2]);
  if (n.squaredNorm() <= 0) return;
  n.normalize();
  // MPR's portal lies where the ray between the centres leaves the Minkowski difference, which
  // need not be the shallowest direction: a cylinder rolling near the end of a 20 m slab got the
  // slab's end face and was pushed 4 m. Against a polyhedron its face axes are tested as well
  // (a separating-axis test through the other shape's support function); the face wins when it
  // needs no deeper push than MPR's direction (libccd's depth includes the two inflations).
  if (b.is_polyhedron()) {
    const FaceAxis face = best_face_axis(b, pb, a, pa);
    if (face.separation > margin) return;
    if (-face.separation <= depth - margin + kFaceAxisSlack) n = pb.orientation * b.polyhedron.face_normals[face.face];
  }
  const Feature fa = support_feature(a, pa, -n);
  const Feature fb = support_feature(b, pb, n);
  contacts_from_features(fa, fb, n, margin, out);
  if (out.count == 0) {
    // Clipping left nothing (features that barely overlap sideways): keep libccd's point.
    const Vec3 p(pos.v[0], pos.v[1], pos.v[2]);
    const Real s = margin - depth;
    out.normal = n;
    out.frame = NormalFrame::body_b;
    out.add({p + 0.5 * s * n, p - 0.5 * s * n, 0, 0, s});
  }
}

}  // namespace moreau::narrow
