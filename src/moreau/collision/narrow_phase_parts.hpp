#pragma once
// Internal pieces of the narrow phase, shared by its source files (not part of the engine's API).
#include <array>
#include <cmath>
#include <limits>

#include "moreau/collision/narrow_phase.hpp"

namespace moreau::narrow {

/// A candidate contact in world space: cores, radii and the separation along the manifold normal;
/// for a normal that follows the cores, the segments the cores lie on (ContactGeometry::on_lines).
struct Candidate {
  Vec3 core_a, core_b;
  Real radius_a = 0, radius_b = 0;
  Real separation = 0;
  bool on_lines = false;
  std::array<Vec3, 2> line_a{Vec3::Zero(), Vec3::Zero()}, line_b{Vec3::Zero(), Vec3::Zero()};

  /// The same candidate with its cores on segments [a0, a1] and [b0, b1] (a segment may be a point).
  Candidate along(const Vec3& a0, const Vec3& a1, const Vec3& b0, const Vec3& b1) const {
    Candidate c = *this;
    c.on_lines = true;
    c.line_a = {a0, a1};
    c.line_b = {b0, b1};
    return c;
  }
};

/// Whether two core segments (directions da, db; a point has none) lie along each other
/// (parallel capsules): |cosine| above 0.995.
inline bool lie_along(const Vec3& da, const Vec3& db) {
  return da.squaredNorm() > 0 && db.squaredNorm() > 0 && std::abs(da.normalized().dot(db.normalized())) > 0.995;
}

/// Up to 64 candidates with one world normal (B to A), reduced to four at the end.
struct Candidates {
  static constexpr int capacity = 64;
  std::array<Candidate, capacity> items;
  int count = 0;
  Vec3 normal = Vec3::UnitY();
  NormalFrame frame = NormalFrame::body_b;

  void add(const Candidate& c) {
    if (count < capacity) items[count++] = c;
  }
};

/// The extreme feature of a shape in a direction: a face polygon, an edge, or a point, with the
/// shape's rounding radius (sphere and capsule features are points of their cores).
struct Feature {
  static constexpr int capacity = 32;
  std::array<Vec3, capacity> points;
  int count = 0;
  bool is_face = false;
  Vec3 face_normal = Vec3::Zero();  // outward, when is_face
  Real radius = 0;
};

/// The feature of `shape` (posed) furthest along world direction `direction`.
Feature support_feature(const Shape& shape, const Pose& pose, const Vec3& direction);

enum class Reference { automatic, a, b };

/// Builds contacts from features along normal n (B to A): the reference is the feature whose face
/// is better aligned with n (or the one named); the other is clipped against its side planes;
/// points with separation below `margin` are kept. Without a face on either side, the closest
/// points of the two features make one contact.
void contacts_from_features(const Feature& fa, const Feature& fb, const Vec3& n, Real margin, Candidates& out,
                            Reference reference = Reference::automatic);

/// Reduces the candidates to at most four that keep the deepest point and span the largest area.
ContactManifold reduce_to_manifold(const Candidates& c, const Pose& pose_a, const Pose& pose_b);

/// Closest points of segments [p0, p1] and [q0, q1] (a segment may be a point).
void closest_points_of_segments(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1, Vec3& on_p,
                                Vec3& on_q);

/// The deepest separation of one polyhedron from the face planes of the other, and that face.
struct FaceAxis {
  Real separation = -std::numeric_limits<Real>::infinity();
  Index face = -1;
};

/// The face plane of polyhedron `self` from which convex `other` (any shape, through its support
/// function) is separated the most: the shallowest of `self`'s face axes.
FaceAxis best_face_axis(const Shape& self, const Pose& pose_self, const Shape& other, const Pose& pose_other);

/// What a separating-axis test of two overlapping polyhedra found: the best face axis of each
/// and the best edge-edge axis (oriented from A to B, with the two edge directions crossed).
struct SeparatingAxes {
  FaceAxis face_a, face_b;
  Real edge_separation = -std::numeric_limits<Real>::infinity();
  Vec3 edge_axis = Vec3::Zero(), edge_dir_a = Vec3::Zero(), edge_dir_b = Vec3::Zero();
};

/// Box/hull against box/hull by separating axes.
void collide_polyhedra(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb, Real margin,
                       Candidates& out);
/// Box against box: the same axes and contacts as collide_polyhedra, each axis's separation in
/// closed form from the boxes' rotation matrices (box_contacts.cpp).
void collide_boxes(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb, Real margin, Candidates& out);
/// The contacts of overlapping polyhedra from their axes: an edge-edge contact when an edge axis
/// separates clearly more than any face, else the incident face clipped against the reference face.
void contacts_from_axes(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb, Real margin,
                        const SeparatingAxes& axes, Candidates& out);
/// Sphere A against box/hull B.
void collide_sphere_polyhedron(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb, Real margin,
                               Candidates& out);
/// A capsule (A) against a box or hull (B) by the closest points of its core: the point of the
/// core deepest in B or nearest it (a convex function along the core, minimised by golden-section
/// search), and the farthest points of the core towards each end that face the same side of B,
/// so a capsule lying on a face rests on two points.
void collide_capsule_polyhedron(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb, Real margin,
                                Candidates& out);
/// Any convex pair by Minkowski portal refinement (libccd) for the normal, then feature clipping.
void collide_convex_mpr(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb, Real margin,
                        Candidates& out);

}  // namespace moreau::narrow
