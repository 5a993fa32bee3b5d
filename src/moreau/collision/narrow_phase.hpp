#pragma once
// Narrow phase: the contact manifold (up to four points) between two posed shapes, found once per
// step with a margin and re-evaluated every substep from body-frame points (Mueller et al. 2020,
// sec. 3.5: "contact pairs are collected once per time step and re-evaluated in each substep").
//
// Convention: the normal points from B to A. Each point pair is stored as a "core" point per body
// (body frame) plus a radius: the surface point of A is x_a + q_a core_a - radius_a n and that of
// B is x_b + q_b core_b + radius_b n, so a sphere or capsule that rolls keeps touching with its
// current lowest point. The separation (p_a - p_b) . n is negative in penetration.
//
// Pairs and methods:
//   sphere/capsule with sphere/capsule  closest points of the cores (points or segments); the
//                                       normal follows the cores every substep, the points
//                                       sliding along the segments
//   anything with a plane               the shape's points below the plane (vertices, segment ends,
//                                       the rim of a cylinder)
//   box/hull with box/hull              separating axes (face normals and edge-edge cross
//                                       products), then the incident face clipped against the
//                                       reference face's side planes (Gregorius, GDC 2013/2015)
//   sphere with box/hull                closest point of the polyhedron to the centre
//   other pairs (capsule or cylinder    Minkowski portal refinement (libccd, Snethen 2008) for the
//   with box/hull, cylinder pairs)      normal, then the same feature clipping
#include <array>
#include <vector>

#include "moreau/math/pose.hpp"
#include "moreau/collision/shape.hpp"

namespace moreau {

/// Which frame a contact normal is stored in (it turns with that body between substeps), or
/// whether it is recomputed from the cores each substep (round against round).
enum class NormalFrame : std::uint8_t { body_a, body_b, cores };

struct ContactGeometry {
  Vec3 core_a = Vec3::Zero(), core_b = Vec3::Zero();  // body frames
  Real radius_a = 0, radius_b = 0;                    // m
  Vec3 normal = Vec3::UnitY();                        // unit, in the frame `frame` names (B to A)
  // In the cores frame, the segments the cores lie on (body frames; a segment may be a point: a
  // sphere's centre, a cylinder's rim point): a capsule's or a cylinder side's axis, an edge. The
  // cores then slide along them to their closest points at the current poses, so a rope segment
  // sliding along a drum keeps its normal square to the drum's axis (with fixed cores the normal
  // tilted towards the detected point and pushed the rope further along: it slid off).
  bool on_lines = false;
  bool parallel_lines = false;  // the segments lay along each other at detection (each point keeps its place on A)
  std::array<Vec3, 2> line_a{Vec3::Zero(), Vec3::Zero()}, line_b{Vec3::Zero(), Vec3::Zero()};
};

struct ContactManifold {
  std::array<ContactGeometry, 4> points;
  int count = 0;
  NormalFrame frame = NormalFrame::body_b;
};

/// Contacts between A and B whose separation is below `margin` (m); count = 0 if none.
ContactManifold collide_shapes(const Shape& a, const Pose& pose_a, const Shape& b, const Pose& pose_b,
                               Real margin);

/// The same manifold seen from the other body: A and B swapped, the normal reversed.
void swap_sides(ContactManifold& m);

/// Contacts of a convex shape (A) with a triangle mesh (B), one manifold per triangle whose slab it
/// touches (mesh_shape.hpp), appended to `out`.
void collide_with_mesh(const Shape& convex, const Pose& pose, const Shape& mesh, const Pose& mesh_pose,
                       Real margin, std::vector<ContactManifold>& out);

/// World-space core points of a contact in the current poses (slid along their lines in the cores
/// frame).
struct CorePoints {
  Vec3 a, b;
};
CorePoints contact_cores(NormalFrame frame, const ContactGeometry& c, const Pose& pose_a, const Pose& pose_b);

/// World-space unit normal (B to A) of a contact in the current poses, given its cores there.
Vec3 contact_normal(NormalFrame frame, const ContactGeometry& c, const Pose& pose_a, const Pose& pose_b,
                    const CorePoints& cores);
/// The same, finding the cores.
inline Vec3 contact_normal(NormalFrame frame, const ContactGeometry& c, const Pose& pose_a, const Pose& pose_b) {
  return contact_normal(frame, c, pose_a, pose_b, contact_cores(frame, c, pose_a, pose_b));
}

}  // namespace moreau
