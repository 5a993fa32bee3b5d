// A rigid manifold's rows (constraints/contact_rows.hpp) against the geometry they describe: a
// turned box's corner below a fixed plane. The normal row's value is the corner's depth, the
// friction rows' values its slip since the substep began, the three directions are orthonormal,
// and the rows' gradients with respect to the box (point rows at the corner's offset) are the
// derivatives of those values.
#include <gtest/gtest.h>

#include "moreau/constraints/contact_rows.hpp"
#include "moreau/rigid/rigid_bodies.hpp"
#include "moreau/collision/rigid_contacts.hpp"

namespace moreau {
namespace {

struct CornerOnPlane {
  RigidBodyState bodies;
  std::vector<Vec3> start_position{2, Vec3::Zero()};  // the substep's start
  std::vector<Quat> start_orientation{2, Quat::Identity()};
  RigidManifold manifold;
  std::array<RigidContactPoint, 2> points;
  Vec3 corner = Vec3(0.1, -0.1, 0.1);  // box frame

  CornerOnPlane() {
    bodies.resize(2);
    bodies.orientation[0] = Quat(Eigen::AngleAxis<Real>(0.3, Vec3(1, 0, 1).normalized()));
    bodies.position[0] = Vec3(0.2, 0, -0.1) - bodies.orientation[0] * corner + Vec3(0, -0.004, 0);  // 4 mm deep
    start_position[0] = bodies.position[0] - Vec3(0.003, 0, 0.001);  // slid 3 mm along x, 1 along z
    start_orientation[0] = bodies.orientation[0];
    bodies.position[1] = Vec3::Zero();
    bodies.orientation[1] = Quat::Identity();
    manifold.body_a = 0;
    manifold.body_b = 1;
    manifold.count = 2;
    manifold.frame = NormalFrame::body_b;
    manifold.static_friction = 0.6;
    const Vec3 world_corner = bodies.position[0] + bodies.orientation[0] * corner;
    points[0].geometry.core_a = corner;
    points[0].geometry.core_b = Vec3(world_corner.x(), 0, world_corner.z());
    points[1].geometry.core_a = -corner;  // the opposite corner, above the plane
    points[1].geometry.core_b = Vec3::Zero();
  }
  ContactRows rows() {
    return manifold_rows(manifold, points.data(), bodies, SubstepStart{nullptr, start_position.data(), start_orientation.data()});
  }
};

TEST(ContactRows, CornerBelowAPlaneHasItsDepthSlipAndDerivatives) {
  CornerOnPlane scene;
  const ContactRows rows = scene.rows();
  ASSERT_EQ(rows.points, 1);
  EXPECT_EQ(rows.point[0], 0);
  EXPECT_EQ(rows.static_friction, 0.6);
  // Values of order 0.1 m built from a few products: round-off is a few ulps (~1e-17 m each), so
  // 1e-15 m holds any correct evaluation and fails a wrong offset or sign by orders of magnitude.
  EXPECT_NEAR(rows.C[0], -0.004, 1e-15);
  const Vec3 slip(0.003, 0, 0.001);
  for (int r = 0; r < 3; ++r) {
    EXPECT_NEAR(rows.direction[r].norm(), 1, 1e-15);
    for (int q = r + 1; q < 3; ++q) EXPECT_NEAR(rows.direction[r].dot(rows.direction[q]), 0, 1e-15);
  }
  EXPECT_EQ(rows.direction[0], Vec3::UnitY());
  EXPECT_NEAR(rows.C[1], slip.dot(rows.direction[1]), 1e-15);
  EXPECT_NEAR(rows.C[2], slip.dot(rows.direction[2]), 1e-15);

  // Central differences over the box's position and a world rotation vector; step 1e-6 leaves a
  // truncation error ~1e-12 m per unit, far below the 1e-8 tolerance.
  const Real eps = 1e-6;
  for (int k = 0; k < 6; ++k) {
    CornerOnPlane plus, minus;
    const Vec3 d = eps * Vec3::Unit(k % 3);
    if (k < 3) {
      plus.bodies.position[0] += d;
      minus.bodies.position[0] -= d;
    } else {
      plus.bodies.orientation[0] = Quat(Eigen::AngleAxis<Real>(eps, d / eps)) * plus.bodies.orientation[0];
      minus.bodies.orientation[0] = Quat(Eigen::AngleAxis<Real>(-eps, d / eps)) * minus.bodies.orientation[0];
    }
    const ContactRows p = plus.rows(), m = minus.rows();
    for (int r = 0; r < 3; ++r) {
      const Vec3& dir = rows.direction[r];
      const Real analytic = k < 3 ? dir(k) : rows.offset_a[r].cross(dir)(k - 3);
      EXPECT_NEAR((p.C[r] - m.C[r]) / (2 * eps), analytic, 1e-8) << "row " << r << " coordinate " << k;
    }
  }
}

}  // namespace
}  // namespace moreau
