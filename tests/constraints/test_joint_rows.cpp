// Every joint type's row blocks against central differences of their own C: the Jacobians the
// Gauss-Seidel pass, the direct tree solver and a velocity-level solver read are the derivatives
// of the values they are given with.
#include <gtest/gtest.h>
#include <fmt/format.h>

#include <vector>

#include "moreau/constraints/joints/joint.hpp"
#include "moreau/model/state.hpp"

namespace moreau {
namespace {

struct Collect final : BodyRowSink {
  std::vector<BodyRows> blocks;
  void take(const BodyRows& rows) override { blocks.push_back(rows); }
};

std::vector<BodyRows> rows_at(const Joint& j, const State& s) {
  Collect c;
  joint_rows({s, j, 1e-3, 0.1, JointRowSet::all}, c);
  return c.blocks;
}

Quat turned(const Quat& q, const Vec3& theta) {
  const Real angle = theta.norm();
  return angle == 0 ? q : Quat(Eigen::AngleAxis<Real>(angle, theta / angle)) * q;
}

// Two bodies at general poses, the joint's frames in each body frame.
State two_bodies(const Quat& qa, const Quat& qb, const Vec3& xb) {
  State s;
  s.rigid.resize(2);
  s.rigid.position[0] = Vec3(0.1, -0.2, 0.3);
  s.rigid.orientation[0] = qa;
  s.rigid.position[1] = xb;
  s.rigid.orientation[1] = qb;
  return s;
}

// Both bodies turned about unrelated axes, apart by a general offset: no row is at a special point.
State general_pose() {
  return two_bodies(Quat(Eigen::AngleAxis<Real>(0.7, Vec3(0, 1, 1).normalized())),
                    Quat(Eigen::AngleAxis<Real>(-0.5, Vec3(1, 0, 2).normalized())), Vec3(0.5, 0.4, -0.1));
}

Joint joint_of(JointType type) {
  Joint j;
  j.type = type;
  j.ends[0] = {BodyEndKind::body, 0, Vec3(0.3, 0.1, -0.2), Quat(Eigen::AngleAxis<Real>(0.4, Vec3(1, 2, 3).normalized()))};
  j.ends[1] = {BodyEndKind::body, 1, Vec3(-0.1, 0.25, 0.05), Quat(Eigen::AngleAxis<Real>(-0.3, Vec3(2, -1, 1).normalized()))};
  return j;
}

// Compares every block's Jacobian with central differences of C over the 12 coordinates (dx and
// a world rotation vector per body). The step 1e-6 makes the truncation error ~1e-12 and the
// rounding error ~1e-10 for values of order 1, so 1e-7 is a failure of the derivative, not of the
// difference.
void expect_jacobians_match(const Joint& j, const State& s, size_t expected_blocks) {
  const std::vector<BodyRows> at = rows_at(j, s);
  ASSERT_EQ(at.size(), expected_blocks);
  const Real eps = 1e-6;
  for (int e = 0; e < 2; ++e)
    for (int k = 0; k < 6; ++k) {
      State plus = s, minus = s;
      const Vec3 d = eps * Vec3::Unit(k % 3);
      if (k < 3) {
        plus.rigid.position[e] += d;
        minus.rigid.position[e] -= d;
      } else {
        plus.rigid.orientation[e] = turned(s.rigid.orientation[e], d);
        minus.rigid.orientation[e] = turned(s.rigid.orientation[e], -d);
      }
      const std::vector<BodyRows> p = rows_at(j, plus), m = rows_at(j, minus);
      ASSERT_EQ(p.size(), at.size());
      ASSERT_EQ(m.size(), at.size());
      for (size_t b = 0; b < at.size(); ++b)
        for (int r = 0; r < at[b].size(); ++r) {
          const Real numeric = (p[b].C(r) - m[b].C(r)) / (2 * eps);
          EXPECT_NEAR(at[b].jacobian[e](r, k), numeric, 1e-7)
              << fmt::format("block {} (slot {}) row {} end {} coordinate {}", b, at[b].slot, r, e, k);
        }
    }
}

TEST(JointRows, FixedJointRowsAreTheDerivativesOfTheirValues) {
  const State s = general_pose();
  expect_jacobians_match(joint_of(JointType::fixed), s, 2);
}

TEST(JointRows, HingeRowsAreTheDerivativesOfTheirValues) {
  // Alignment and attachment at a general pose.
  Joint j = joint_of(JointType::hinge);
  expect_jacobians_match(j, general_pose(), 2);
  // The angle's limit and drive rows turn about a's axis: their derivative is exact where the axes
  // are aligned, so b's frame is a's turned by 0.8 rad about it, beyond the upper limit 0.5.
  j.limited = true;
  j.lower = -0.5;
  j.upper = 0.5;
  j.drive = DriveMode::velocity;
  j.drive_target = 2;
  const Quat qa(Eigen::AngleAxis<Real>(0.7, Vec3(0, 1, 1).normalized()));
  const Quat frame_a = qa * j.ends[0].frame;
  const Quat qb = frame_a * Quat(Eigen::AngleAxis<Real>(0.8, Vec3::UnitX())) * j.ends[1].frame.conjugate();
  expect_jacobians_match(j, two_bodies(qa, qb, Vec3(0.5, 0.4, -0.1)), 4);
}

TEST(JointRows, SphericalRowsWithSwingLimitAreTheDerivativesOfTheirValues) {
  Joint j = joint_of(JointType::spherical);
  j.swing_limited = true;
  j.swing = 0.2;
  const State s = general_pose();
  expect_jacobians_match(j, s, 2);
}

TEST(JointRows, PrismaticRowsAreTheDerivativesOfTheirValues) {
  Joint j = joint_of(JointType::prismatic);
  j.limited = true;
  j.lower = -0.1;
  j.upper = 0.05;
  j.drive = DriveMode::position;
  j.drive_target = 0.02;
  const State s = general_pose();
  expect_jacobians_match(j, s, 4);
}

TEST(JointRows, DistanceRowsAreTheDerivativesOfTheirValues) {
  Joint j = joint_of(JointType::distance);
  const State s = general_pose();
  j.lower = j.upper = 0.3;  // a rod: one equality row
  expect_jacobians_match(j, s, 1);
  j.lower = 0.05;  // a rope longer than the gap: no row
  j.upper = 2;
  expect_jacobians_match(j, s, 0);
  j.upper = 0.2;  // stretched beyond its maximum: one row that may only pull
  const std::vector<BodyRows> rows = rows_at(j, s);
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_GT(rows[0].C(0), 0);
  EXPECT_EQ(rows[0].upper(0), 0);
  EXPECT_EQ(rows[0].lower(0), -std::numeric_limits<Real>::infinity());
  expect_jacobians_match(j, s, 1);
}

}  // namespace
}  // namespace moreau
