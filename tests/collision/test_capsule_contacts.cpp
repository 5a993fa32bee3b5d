// A capsule against a box by the closest points of its core: the contact normal is the box's own
// (not tilted towards the box's centre), and a capsule lying on a face rests on two points.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "moreau/collision/narrow_phase.hpp"
#include "moreau/collision/shape.hpp"

namespace moreau {
namespace {

// A 0.4 x 0.2 x 0.4 m box at the origin; capsules of radius 1 cm and length 5 cm (plus caps)
// lying along z, sunk 1 mm into its top.
const Shape kBox = make_box(Vec3(0.2, 0.1, 0.2));
const Shape kCapsule = make_capsule(0.01, 0.025);
const Quat kAlongZ(Eigen::AngleAxisd(kPi / 2, Vec3::UnitX()));  // the capsule's y axis along z

TEST(CapsuleContacts, ACapsuleOverABoxEdgeTakesTheTopFacesNormal) {
  // Its core ends right above the edge z = -0.2 (the capsule hangs over it): the normal is
  // straight up, though the line between the centres leans 64 degrees from it.
  const Pose capsule{Vec3(0, 0.109, -0.225), kAlongZ}, box{Vec3::Zero(), Quat::Identity()};
  const ContactManifold m = collide_shapes(kCapsule, capsule, kBox, box, 0.005);
  ASSERT_GE(m.count, 1);
  for (int k = 0; k < m.count; ++k) {
    const Vec3 n = contact_normal(m.frame, m.points[k], capsule, box);
    EXPECT_NEAR(n.y(), 1, 1e-9) << k;
  }
}

TEST(CapsuleContacts, ACapsuleLyingOnAFaceRestsOnTwoPoints) {
  const Pose capsule{Vec3(0.05, 0.109, 0.03), kAlongZ}, box{Vec3::Zero(), Quat::Identity()};
  const ContactManifold m = collide_shapes(kCapsule, capsule, kBox, box, 0.005);
  ASSERT_EQ(m.count, 2);
  Real z[2];
  for (int k = 0; k < 2; ++k) {
    EXPECT_NEAR(contact_normal(m.frame, m.points[k], capsule, box).y(), 1, 1e-12);
    z[k] = capsule.to_world(m.points[k].core_a).z();
  }
  EXPECT_NEAR(std::abs(z[0] - z[1]), 0.05, 1e-9);  // the two ends of the core
}

}  // namespace
}  // namespace moreau
