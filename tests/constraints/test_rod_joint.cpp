// The rod junction's rows (constraints/joints/rod_joint.cpp): their Jacobians against central
// differences at a bent, twisted and stretched junction, where an approximate Jacobian that left
// out the turn of the measuring frame would be off by the order of the strain.
#include <gtest/gtest.h>

#include <vector>

#include "moreau/constraints/joints/joint.hpp"
#include "moreau/model/state.hpp"

namespace moreau {
namespace {

class Collect final : public BodyRowSink {
 public:
  void take(const BodyRows& rows) override { blocks.push_back(rows); }
  std::vector<BodyRows> blocks;
};

std::vector<BodyRows> rows_at(const Joint& j, const State& s) {
  Collect c;
  joint_rows({s, j, 0.01, 0, JointRowSet::all}, c);
  return c.blocks;
}

TEST(RodJoint, JacobiansMatchCentralDifferencesAtAStrainedJunction) {
  Joint j;
  j.type = JointType::rod;
  j.rod_compliance = Vec3(1e-6, 2e-6, 3e-6);
  j.rod_angular_compliance = Vec3(1e-3, 2e-3, 3e-3);
  for (int e = 0; e < 2; ++e) j.ends[e].kind = BodyEndKind::body, j.ends[e].index = e;
  j.ends[0].anchor = Vec3(0, 0.05, 0);
  j.ends[1].anchor = Vec3(0.01, -0.05, 0.02);
  j.ends[0].frame = Quat(Eigen::AngleAxisd(0.3, Vec3(1, 2, 3).normalized()));
  j.ends[1].frame = Quat(Eigen::AngleAxisd(-0.7, Vec3(-2, 1, 0.5).normalized()));
  State s;
  s.rigid.resize(2);
  s.rigid.position = {Vec3(0.1, 0.2, 0.3), Vec3(0.13, 0.31, 0.27)};
  // Orientations that leave the frames 0.4 rad apart (bent and twisted) and the anchors 2 cm apart.
  s.rigid.orientation = {Quat(Eigen::AngleAxisd(0.9, Vec3(0, 1, 1).normalized())),
                         Quat(Eigen::AngleAxisd(0.4, Vec3(1, 0.2, -0.3).normalized())) *
                             Quat(Eigen::AngleAxisd(0.9, Vec3(0, 1, 1).normalized())) * j.ends[0].frame *
                             j.ends[1].frame.conjugate()};
  const std::vector<BodyRows> base = rows_at(j, s);
  ASSERT_EQ(base.size(), 2u);
  EXPECT_GT(base[0].C.norm(), 0.3);
  EXPECT_GT(base[1].C.norm(), 0.01);
  const Real step = 1e-6;
  for (int e = 0; e < 2; ++e)
    for (int k = 0; k < 6; ++k) {
      State plus = s, minus = s;
      if (k < 3) {
        plus.rigid.position[e][k] += step;
        minus.rigid.position[e][k] -= step;
      } else {
        const Vec3 axis = Vec3::Unit(k - 3);
        plus.rigid.orientation[e] = (Quat(Eigen::AngleAxisd(step, axis)) * s.rigid.orientation[e]).normalized();
        minus.rigid.orientation[e] = (Quat(Eigen::AngleAxisd(-step, axis)) * s.rigid.orientation[e]).normalized();
      }
      const std::vector<BodyRows> p = rows_at(j, plus), m = rows_at(j, minus);
      for (int b = 0; b < 2; ++b) {
        const BodyRows::Vector numeric = (p[b].C - m[b].C) / (2 * step);
        const BodyRows::Vector analytic = base[b].jacobian[e].col(k);
        EXPECT_LT((numeric - analytic).norm(), 1e-8 * (1 + analytic.norm())) << "block " << b << ", end " << e << ", column " << k;
      }
    }
}

}  // namespace
}  // namespace moreau
