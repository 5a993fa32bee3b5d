// Rod junction: where two segments of a Cosserat rod meet (Deul, Kugelstadt, Weiler, Bender 2018,
// "Direct Position-Based Solver for Stiff Rods": the segments are rigid bodies and the rod's
// strains live at the junctions). The two end frames coincide in the rod's rest shape, with x
// along the rod, so any rest curvature and twist are in the frames.
//   bend-twist      C = 2 s vec(f_b^-1 f_a), the relative rotation in b's frame (rad, 3 rows):
//                   twist about x, bending about y and z
//   stretch-shear   C = R_a^T (p_a - p_b), the anchors' gap in a's frame (m, 3 rows):
//                   stretch along x, shear along y and z
// With the junction's share l of the rod's length (the distance between the segment centres),
// the rod's energy (l/2) (k^T K k + g^T S g) for curvature and twist k = theta/l and strain
// g = gap/l gives the compliances per axis: l/(G J), l/(E I_y), l/(E I_z) and l/(E A),
// l/(G A), l/(G A) (scene/build_rod.cpp).
// The Jacobians are exact, the turn of the frames included: a twisted rod buckles by the
// coupling of its twisting moment with the turn of the frame it is measured in (Greenhill), which
// an approximate Jacobian gets wrong in proportion to the twist per junction.
//   bend-twist     turning a by dtheta (world) makes q = f_b^-1 f_a = (w, v) into
//                  q + 1/2 [R_b^T dtheta, 0] q, whose vector part grows by 1/2 (w I - [v]x) R_b^T
//                  dtheta; turning b takes the same away: J_a,theta = s (w I - [v]x) R_b^T = -J_b,theta
//   stretch-shear  J_a = [R_a^T, R_a^T ([d]x - [r_a]x)], J_b = [-R_a^T, R_a^T [r_b]x] with d = p_a - p_b
//                  and r the anchors' offsets from the centres (R_a^T d turns with a)
// A pinned rod end (rod_pinned) keeps the stretch-shear rows only. A junction's damping_time damps
// its strain rates in proportion to its stiffness (Kelvin-Voigt, set_damping). Every row is an
// equality row the direct tree solver may take.
#include "moreau/constraints/joints/joint_row_blocks.hpp"
#include "moreau/constraints/joints/joint_type_rules.hpp"

namespace moreau {

namespace {

BodyRows bend_twist_rows(const Joint& j, const JointEndPose& a, const JointEndPose& b) {
  BodyRows rows = BodyRows::zero(j.bodies(), 3, JointSlot::orientation);
  const Quat q = b.frame().conjugate() * a.frame();
  const Real s = q.w() >= 0 ? 1 : -1;
  rows.C = 2 * s * q.vec();
  const Mat3 Ja = s * (q.w() * Mat3::Identity() - cross_matrix(q.vec())) * b.frame().toRotationMatrix().transpose();
  rows.jacobian[0].rightCols<3>() = Ja;
  rows.jacobian[1].rightCols<3>() = -Ja;
  rows.compliance = j.rod_angular_compliance;
  return rows;
}

BodyRows stretch_shear_rows(const Joint& j, const JointEndPose& a, const JointEndPose& b) {
  BodyRows rows = BodyRows::zero(j.bodies(), 3, JointSlot::position);
  const Mat3 Rt = a.frame().toRotationMatrix().transpose();
  const Vec3 d = a.anchor() - b.anchor();
  rows.C = Rt * d;
  rows.jacobian[0].leftCols<3>() = Rt;
  rows.jacobian[0].rightCols<3>() = Rt * (cross_matrix(d) - cross_matrix(a.offset()));
  rows.jacobian[1].leftCols<3>() = -Rt;
  rows.jacobian[1].rightCols<3>() = Rt * cross_matrix(b.offset());
  rows.compliance = j.rod_compliance;
  return rows;
}

void rod_rows(const JointRowContext& c, BodyRowSink& sink) {
  if (!c.wants_equality()) return;
  if (!c.joint.rod_pinned) {
    BodyRows bend_twist = bend_twist_rows(c.joint, end_pose_a(c), end_pose_b(c));
    set_damping(bend_twist, c);
    sink.take(bend_twist);
  }
  // The bend-twist rows moved the bodies: the gap is read at the new poses.
  BodyRows stretch_shear = stretch_shear_rows(c.joint, end_pose_a(c), end_pose_b(c));
  set_damping(stretch_shear, c);
  sink.take(stretch_shear);
}

JointError rod_error(const Joint& j, const JointEndPose& a, const JointEndPose& b) {
  return {(a.anchor() - b.anchor()).norm(), j.rod_pinned ? Real(0) : orientation_error(a.frame(), b.frame()).norm()};
}

}  // namespace

const JointTypeRules kRodJoint{rod_rows, [](const Joint& j) { return j.rod_pinned ? 3 : 6; },
                               [](const Joint&) { return false; }, rod_error, no_coordinate};

}  // namespace moreau
