// Mass properties, convex hulls and the narrow phase of rigid bodies, against hand values.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "moreau/collision/narrow_phase.hpp"
#include "moreau/collision/shape.hpp"

namespace moreau {
namespace {

TEST(RigidShapes, PrimitiveMassPropertiesMatchClosedForms) {
  // Box 2a x 2b x 2c: V = 8abc, I_xx = V (b^2 + c^2)/3.
  const MassProperties box = mass_properties(make_box(Vec3(0.5, 1.0, 1.5)));
  EXPECT_NEAR(box.volume, 6.0, 1e-12);
  EXPECT_NEAR(box.inertia(0, 0), 6.0 * (1.0 + 2.25) / 3, 1e-12);
  // Sphere: I = 2/5 V r^2.
  const MassProperties sphere = mass_properties(make_sphere(0.3));
  EXPECT_NEAR(sphere.inertia(1, 1), 0.4 * sphere.volume * 0.09, 1e-15);
  // Cylinder along y: I_yy = V r^2/2, I_xx = V (3 r^2 + L^2)/12.
  const MassProperties cyl = mass_properties(make_cylinder(0.2, 0.5));
  EXPECT_NEAR(cyl.volume, kPi * 0.04 * 1.0, 1e-14);
  EXPECT_NEAR(cyl.inertia(0, 0), cyl.volume * (3 * 0.04 + 1.0) / 12, 1e-14);
  // A capsule of zero length is a sphere.
  const MassProperties ball = mass_properties(make_capsule(0.3, 0));
  EXPECT_NEAR(ball.volume, sphere.volume, 1e-14);
  EXPECT_NEAR(ball.inertia(0, 0), sphere.inertia(0, 0), 1e-14);
  EXPECT_NEAR(ball.inertia(1, 1), sphere.inertia(1, 1), 1e-14);
}

TEST(RigidShapes, CapsuleInertiaMatchesNumericalIntegration) {
  // Monte Carlo-free check: integrate x^2 + z^2 (about y) and y^2 + z^2 (about x) on a fine grid.
  const Real r = 0.2, a = 0.35;
  const int n = 200;
  const Real h = 2 * (r + a) / n;
  Real volume = 0, Ixx = 0, Iyy = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k) {
        const Vec3 p(-r + (i + 0.5) * (2 * r / n), -(r + a) + (j + 0.5) * h, -r + (k + 0.5) * (2 * r / n));
        const Real axial = std::clamp(p.y(), -a, a);
        if ((p - Vec3(0, axial, 0)).norm() > r) continue;
        const Real dv = (2 * r / n) * h * (2 * r / n);
        volume += dv;
        Ixx += (p.y() * p.y() + p.z() * p.z()) * dv;
        Iyy += (p.x() * p.x() + p.z() * p.z()) * dv;
      }
  const MassProperties m = mass_properties(make_capsule(r, a));
  // The grid resolves the curved surface to about 0.5 % at 200 cells per side.
  EXPECT_NEAR(m.volume, volume, 5e-3 * volume);
  EXPECT_NEAR(m.inertia(0, 0), Ixx, 5e-3 * Ixx);
  EXPECT_NEAR(m.inertia(1, 1), Iyy, 5e-3 * Iyy);
}

TEST(RigidShapes, HullOfRotatedBoxCornersIsThatBox) {
  const Quat q(Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()));
  const Vec3 e(0.2, 0.5, 0.9), offset(1, -2, 0.5);
  std::vector<Vec3> points;
  for (int k = 0; k < 8; ++k)
    points.push_back(offset + q * Vec3((k & 1 ? 1 : -1) * e.x(), (k & 2 ? 1 : -1) * e.y(), (k & 4 ? 1 : -1) * e.z()));
  points.push_back(offset);  // an interior point qhull must drop
  Shape s;
  s.type = ShapeType::convex_hull;
  s.polyhedron = convex_hull(points);
  EXPECT_EQ(s.polyhedron.vertices.size(), 8u);
  EXPECT_EQ(s.polyhedron.faces.size(), 6u);   // coplanar triangles merged into quadrilaterals
  EXPECT_EQ(s.polyhedron.edge_directions.size(), 3u);
  MassProperties props = mass_properties(s);
  EXPECT_NEAR(props.volume, 8 * e.prod(), 1e-12);
  EXPECT_NEAR((props.center - offset).norm(), 0, 1e-12);
  const Mat3 R = move_to_principal_frame(s, props);
  EXPECT_NEAR(R.determinant(), 1, 1e-12);
  // Principal moments of the box, in ascending order.
  std::vector<Real> moments{props.inertia(0, 0), props.inertia(1, 1), props.inertia(2, 2)};
  std::sort(moments.begin(), moments.end());
  const Real V = 8 * e.prod();
  std::vector<Real> expected{V / 3 * (e.y() * e.y() + e.z() * e.z()), V / 3 * (e.x() * e.x() + e.z() * e.z()),
                             V / 3 * (e.x() * e.x() + e.y() * e.y())};
  std::sort(expected.begin(), expected.end());
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(moments[k], expected[k], 1e-12);
  // In the principal frame the vertices are centred.
  Vec3 c = Vec3::Zero();
  for (const Vec3& v : s.polyhedron.vertices) c += v;
  EXPECT_NEAR(c.norm(), 0, 1e-12);
}

TEST(RigidShapes, FlatPointsHaveNoHull) {
  std::vector<Vec3> flat{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 0, 1), Vec3(1, 0, 1), Vec3(0.5, 0, 0.5)};
  EXPECT_THROW(convex_hull(flat), std::invalid_argument);
}

// World-space separation of every manifold point.
std::vector<Real> separations(const ContactManifold& m, const Pose& a, const Pose& b) {
  std::vector<Real> out;
  for (int k = 0; k < m.count; ++k) {
    const ContactGeometry& c = m.points[k];
    const Vec3 n = contact_normal(m.frame, c, a, b);
    out.push_back(((a.to_world(c.core_a) - c.radius_a * n) - (b.to_world(c.core_b) + c.radius_b * n)).dot(n));
  }
  return out;
}

TEST(NarrowPhase, BoxRestingOnBoxGivesFourCornersAtThePenetration) {
  const Shape box = make_box(Vec3(0.5, 0.5, 0.5));
  const Pose lower{Vec3::Zero(), Quat::Identity()};
  const Pose upper{Vec3(0.1, 0.99, -0.05), Quat(Eigen::AngleAxisd(0.2, Vec3::UnitY()))};
  const ContactManifold m = collide_shapes(box, upper, box, lower, 0.05);
  ASSERT_EQ(m.count, 4);
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(contact_normal(m.frame, m.points[k], upper, lower).y(), 1, 1e-12);
  for (Real s : separations(m, upper, lower)) EXPECT_NEAR(s, -0.01, 1e-12);
  // The same pair in the other order: the normal flips, the separations do not change.
  const ContactManifold flipped = collide_shapes(box, lower, box, upper, 0.05);
  ASSERT_EQ(flipped.count, 4);
  for (Real s : separations(flipped, lower, upper)) EXPECT_NEAR(s, -0.01, 1e-12);
}

TEST(NarrowPhase, EdgeOnEdgeContactIsOnePointAtTheTrueDistance) {
  // Two unit cubes turned 45 degrees about perpendicular axes meet edge to edge.
  const Shape box = make_box(Vec3(0.5, 0.5, 0.5));
  const Real reach = 0.5 * std::sqrt(2.0);
  const Pose a{Vec3(0, 2 * reach - 0.02, 0), Quat(Eigen::AngleAxisd(kPi / 4, Vec3::UnitZ()))};
  const Pose b{Vec3::Zero(), Quat(Eigen::AngleAxisd(kPi / 4, Vec3::UnitX()))};
  const ContactManifold m = collide_shapes(box, a, box, b, 0.05);
  ASSERT_EQ(m.count, 1);
  EXPECT_NEAR(separations(m, a, b)[0], -0.02, 1e-9);
  EXPECT_NEAR(contact_normal(m.frame, m.points[0], a, b).y(), 1, 1e-9);
}

TEST(NarrowPhase, SphereAgainstBoxFaceEdgeAndInside) {
  const Shape box = make_box(Vec3(1, 1, 1)), ball = make_sphere(0.5);
  const Pose at_box{Vec3::Zero(), Quat::Identity()};
  // Above the top face.
  ContactManifold m = collide_shapes(ball, {Vec3(0.3, 1.4, 0), Quat::Identity()}, box, at_box, 0.01);
  ASSERT_EQ(m.count, 1);
  EXPECT_NEAR(separations(m, {Vec3(0.3, 1.4, 0), Quat::Identity()}, at_box)[0], -0.1, 1e-12);
  // Beyond an edge: the distance to the edge line.
  const Pose edge{Vec3(1.3, 1.3, 0), Quat::Identity()};
  m = collide_shapes(ball, edge, box, at_box, 0.01);
  ASSERT_EQ(m.count, 1);
  EXPECT_NEAR(separations(m, edge, at_box)[0], 0.3 * std::sqrt(2.0) - 0.5, 1e-12);
  // Centre inside: pushed out through the nearest face.
  const Pose inside{Vec3(0.8, 0.1, 0), Quat::Identity()};
  m = collide_shapes(ball, inside, box, at_box, 0.01);
  ASSERT_EQ(m.count, 1);
  EXPECT_NEAR(contact_normal(m.frame, m.points[0], inside, at_box).x(), 1, 1e-12);
  EXPECT_NEAR(separations(m, inside, at_box)[0], -0.7, 1e-12);
}

TEST(NarrowPhase, CapsuleLyingOnBoxTouchesAtBothEnds) {
  // Capsule along x (its y axis turned by 90 degrees) lying on a box; the pair goes through MPR.
  const Shape capsule = make_capsule(0.1, 0.4), box = make_box(Vec3(1, 0.5, 1));
  const Pose cap{Vec3(0.2, 0.595, 0.1), Quat(Eigen::AngleAxisd(kPi / 2, Vec3::UnitZ()))};
  const Pose ground{Vec3::Zero(), Quat::Identity()};
  const ContactManifold m = collide_shapes(capsule, cap, box, ground, 0.02);
  ASSERT_EQ(m.count, 2);
  for (Real s : separations(m, cap, ground)) EXPECT_NEAR(s, -0.005, 1e-6);
  for (int k = 0; k < 2; ++k) EXPECT_NEAR(contact_normal(m.frame, m.points[k], cap, ground).y(), 1, 1e-6);
}

TEST(NarrowPhase, CylinderStandingOnPlaneTouchesOnItsRim) {
  const Shape cylinder = make_cylinder(0.3, 0.5), plane = make_plane();
  const Pose standing{Vec3(0, 0.49, 0), Quat::Identity()};
  const Pose ground{Vec3::Zero(), Quat::Identity()};
  const ContactManifold m = collide_shapes(cylinder, standing, plane, ground, 0.02);
  ASSERT_EQ(m.count, 4);  // eight rim points reduced to the four spanning the largest area
  for (Real s : separations(m, standing, ground)) EXPECT_NEAR(s, -0.01, 1e-12);
  // Lying on its side: a line contact, two points.
  const Pose lying{Vec3(0, 0.29, 0), Quat(Eigen::AngleAxisd(kPi / 2, Vec3::UnitX()))};
  const ContactManifold side = collide_shapes(cylinder, lying, plane, ground, 0.02);
  ASSERT_EQ(side.count, 2);
  for (Real s : separations(side, lying, ground)) EXPECT_NEAR(s, -0.01, 1e-12);
}

TEST(NarrowPhase, CylinderLyingOnALongSlabTouchesItsTopAnywhereAndAtAnyTurn) {
  // A wheel (R = 0.1 m) lying across a 20 m slab, 1 mm deep, at 21 places along it and 32 turns
  // about its own axis, with the 0.7 m margin a wheel rolling at 5 m/s gets (the margin inflates
  // both shapes for MPR). The contact is the slab's top face, two points on the wheel's axis with
  // the radius, at the hand separation. MPR alone, from the centres' ray, took the slab's end face
  // 4.7 m away for some of these poses.
  const Shape wheel = make_cylinder(0.1, 0.15), slab = make_box(Vec3(10, 0.5, 2));
  const Pose ground{Vec3::Zero(), Quat::Identity()};
  int checked = 0;
  for (int i = 0; i <= 20; ++i) {
    for (int k = 0; k < 32; ++k) {
      const Real x = -9.5 + 0.95 * i, turn = 2 * kPi * k / 32;
      const Pose lying{Vec3(x, 0.599, 0), Quat(Eigen::AngleAxisd(turn, Vec3::UnitZ())) *
                                                Quat(Eigen::AngleAxisd(kPi / 2, Vec3::UnitX()))};
      const ContactManifold m = collide_shapes(wheel, lying, slab, ground, 0.7);
      ASSERT_EQ(m.count, 2) << "x " << x << " turn " << turn;
      for (Real sep : separations(m, lying, ground)) EXPECT_NEAR(sep, -0.001, 1e-12) << "x " << x << " turn " << turn;
      for (int p = 0; p < 2; ++p) {
        EXPECT_NEAR(contact_normal(m.frame, m.points[p], lying, ground).y(), 1, 1e-12);
        EXPECT_EQ(m.points[p].radius_a, 0.1);  // the axis with the radius: the contact stays under it as it turns
      }
      ++checked;
    }
  }
  EXPECT_EQ(checked, 21 * 32);
}

TEST(NarrowPhase, SphereOnACylindersSideKeepsItsNormalWhileTheCylinderTurns) {
  // A ball (r = 0.05 m) touching a lying cylinder (R = 0.1 m, axis along z) 60 degrees round from
  // the top, 1 mm deep. The normal is the line from the axis to the ball's centre, taken from the
  // two cores, so it stays that line when the cylinder turns about its axis within the step (a
  // normal fixed in the cylinder would turn with it, 0.3 rad here).
  const Shape ball = make_sphere(0.05), drum = make_cylinder(0.1, 0.3);
  const Vec3 radial(std::sin(kPi / 3), std::cos(kPi / 3), 0);
  const Pose sphere{0.149 * radial, Quat::Identity()};
  const Quat lying(Eigen::AngleAxisd(kPi / 2, Vec3::UnitX()));
  const Pose still{Vec3::Zero(), lying};
  const ContactManifold m = collide_shapes(ball, sphere, drum, still, 0.02);
  ASSERT_EQ(m.count, 1);
  EXPECT_NEAR(separations(m, sphere, still)[0], -0.001, 1e-12);
  EXPECT_NEAR(contact_normal(m.frame, m.points[0], sphere, still).dot(radial), 1, 1e-12);
  const Pose turned{Vec3::Zero(), Quat(Eigen::AngleAxisd(0.3, Vec3::UnitZ())) * lying};
  EXPECT_NEAR(contact_normal(m.frame, m.points[0], sphere, turned).dot(radial), 1, 1e-12);
  EXPECT_NEAR(separations(m, sphere, turned)[0], -0.001, 1e-12);
}

TEST(NarrowPhase, SeparatedBeyondTheMarginGivesNothing) {
  const Shape box = make_box(Vec3(0.5, 0.5, 0.5));
  const Pose a{Vec3(0, 1.2, 0), Quat::Identity()}, b{Vec3::Zero(), Quat::Identity()};
  EXPECT_EQ(collide_shapes(box, a, box, b, 0.1).count, 0);
  EXPECT_EQ(collide_shapes(box, a, box, b, 0.3).count, 4);  // within the margin: speculative points
}

}  // namespace
}  // namespace moreau
