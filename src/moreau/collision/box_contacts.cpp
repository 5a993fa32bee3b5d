// Box against box by separating axes in closed form (Gottschalk, Lin, Manocha 1996, "OBBTree"):
// the projection of a box with rotation R and half extents h onto a unit axis u spans
// c.u +- r(u) with r(u) = sum_k h_k |u . R e_k|, so every candidate axis's separation is
//   s(u) = |u . (c_b - c_a)| - r_a(u) - r_b(u)
// without searching either box for its support vertex. The candidates and the choice between
// them are collide_polyhedra's (polyhedron_contacts.cpp): the three face normals of each box and
// the crossed edge directions, ties broken in the same order, and the contacts built by the same
// clipping (contacts_from_axes).
#include <cmath>

#include "moreau/collision/narrow_phase_parts.hpp"

namespace moreau::narrow {

namespace {

Real half_width(const Mat3& R, const Vec3& h, const Vec3& u) {
  return h.x() * std::abs(u.dot(R.col(0))) + h.y() * std::abs(u.dot(R.col(1))) + h.z() * std::abs(u.dot(R.col(2)));
}

// The best face of box `self` (faces -x, +x, -y, +y, -z, +z as in make_box) against the other box,
// `d` pointing from self's centre to the other's: along axis i the face facing the other box
// separates by |t| - h_i - r_other, t = u_i . d (the -face on a tie, as the generic loop keeps the
// first of equal separations).
FaceAxis best_box_face(const Mat3& R, const Vec3& h, const Mat3& R_other, const Vec3& h_other, const Vec3& d) {
  FaceAxis best;
  for (int i = 0; i < 3; ++i) {
    const Vec3 u = R.col(i);
    const Real t = u.dot(d);
    const Real s = std::abs(t) - h[i] - half_width(R_other, h_other, u);
    if (s > best.separation) best = {s, 2 * i + (t > 0 ? 1 : 0)};
  }
  return best;
}

}  // namespace

void collide_boxes(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb, Real margin, Candidates& out) {
  const Mat3 Ra = pa.orientation.toRotationMatrix(), Rb = pb.orientation.toRotationMatrix();
  const Vec3& ha = a.half_extents;
  const Vec3& hb = b.half_extents;
  const Vec3 d = pb.position - pa.position;
  SeparatingAxes axes;
  axes.face_a = best_box_face(Ra, ha, Rb, hb, d);
  if (axes.face_a.separation > margin) return;
  axes.face_b = best_box_face(Rb, hb, Ra, ha, -d);
  if (axes.face_b.separation > margin) return;
  for (const Vec3& da_local : a.polyhedron.edge_directions) {
    const Vec3 da = Ra * da_local;
    for (const Vec3& db_local : b.polyhedron.edge_directions) {
      const Vec3 db = Rb * db_local;
      Vec3 axis = da.cross(db);
      const Real length = axis.norm();
      if (length < 1e-6) continue;  // parallel edges: a face axis covers them
      axis /= length;
      if (axis.dot(d) < 0) axis = -axis;
      const Real s = axis.dot(d) - half_width(Ra, ha, axis) - half_width(Rb, hb, axis);
      if (s > margin) return;
      if (s > axes.edge_separation) axes.edge_separation = s, axes.edge_axis = axis, axes.edge_dir_a = da, axes.edge_dir_b = db;
    }
  }
  contacts_from_axes(a, pa, b, pb, margin, axes, out);
}

}  // namespace moreau::narrow
