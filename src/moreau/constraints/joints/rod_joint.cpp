// Rod junction: where two segments of a Cosserat rod meet (Deul, Kugelstadt, Weiler, Bender 2018,
// "Direct Position-Based Solver for Stiff Rods": the segments are rigid bodies and the rod's
// strains live at the junctions). The two end frames coincide in the rod's rest shape, with x
// along the rod, so any rest curvature and twist are in the frames.
//   bend-twist      C = 2 s vec(f_b^-1 f_a), the relative rotation in b's frame (rad, 3 rows):
//                   twist about x, bending about y and z
//   stretch-shear   C = f_a^T (p_a - p_b), the anchors' gap in a's frame (m, 3 rows):
//                   stretch along x, shear along y and z
// With the junction's share l of the rod's length (the distance between the segment centres),
// the rod's energy (l/2) (k^T K k + g^T S g) for curvature and twist k = theta/l and strain
// g = gap/l gives the compliances per axis: l/(G J), l/(E I_y), l/(E I_z) and l/(E A),
// l/(G A), l/(G A) (scene/build_rod.cpp). Both blocks are the world-frame rows of a fixed joint
// (joint_row_blocks.hpp) turned into the frame; the frame's own turn is left out of the
// Jacobian, which is exact where C = 0 and second order in the per-junction strain elsewhere.
// A junction's damping_time damps its strain rates in proportion to its stiffness (Kelvin-Voigt,
// set_damping). Every row is an equality row the direct tree solver may take.
#include "moreau/constraints/joints/joint_row_blocks.hpp"
#include "moreau/constraints/joints/joint_type_rules.hpp"

namespace moreau {

namespace {

// Rows R^T C with R^T J: the block's values measured along the axes of the frame R.
BodyRows in_frame(BodyRows rows, const Mat3& R, const Vec3& compliance) {
  rows.C = R.transpose() * rows.C;
  for (BodyRows::Jacobian& J : rows.jacobian) J = R.transpose() * J;
  rows.compliance = compliance;
  return rows;
}

void rod_rows(const JointRowContext& c, BodyRowSink& sink) {
  if (!c.wants_equality()) return;
  const JointEndPose a = end_pose_a(c), b = end_pose_b(c);
  BodyRows bend_twist = in_frame(orientation_rows(c.joint, a, b), b.frame().toRotationMatrix(), c.joint.rod_angular_compliance);
  set_damping(bend_twist, c);
  sink.take(bend_twist);
  // The orientation rows moved the bodies: the attachment is read at the new poses.
  const JointEndPose a2 = end_pose_a(c), b2 = end_pose_b(c);
  BodyRows stretch_shear = in_frame(attachment_rows(c.joint, a2, b2), a2.frame().toRotationMatrix(), c.joint.rod_compliance);
  set_damping(stretch_shear, c);
  sink.take(stretch_shear);
}

JointError rod_error(const Joint&, const JointEndPose& a, const JointEndPose& b) {
  return {(a.anchor() - b.anchor()).norm(), orientation_error(a.frame(), b.frame()).norm()};
}

}  // namespace

const JointTypeRules kRodJoint{rod_rows, [](const Joint&) { return 6; }, [](const Joint&) { return false; }, rod_error,
                               no_coordinate};

}  // namespace moreau
