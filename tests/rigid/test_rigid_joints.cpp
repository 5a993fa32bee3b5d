// Joints: each type's corrections remove its violation (a check of their Jacobians and effective
// masses), limits, drives and compliance against analytic values.
#include <gtest/gtest.h>
#include <fmt/format.h>

#include <cmath>

#include "moreau/solvers/xpbd/joint_projection.hpp"
#include "test_helpers.hpp"

namespace moreau {
namespace {

using test::run_steps;
using test::scene_from_json;

// Two boxes joined at (0.5, 0, 0) by a joint of the given JSON; gravity off.
Scene two_boxes(const std::string& joint, const std::string& joint_solver = "direct") {
  return scene_from_json(R"({"name": "joint", "settings": {"gravity": [0, 0, 0], "joint_solver": ")" + joint_solver + R"("},
    "objects": [{"name": "a", "kind": "rigid_body", "shape": {"type": "box", "half_extents": [0.5, 0.2, 0.3]}, "position": [0, 0, 0]},
                {"name": "b", "kind": "rigid_body", "shape": {"type": "box", "half_extents": [0.4, 0.3, 0.2]}, "position": [1, 0, 0], "density": 500}],
    "joints": [)" + joint + "]}");
}

TEST(RigidJoints, ProjectionsRemoveAViolationOfEveryJointType) {
  // Perturb the pose of body b by ~1e-3 (m and rad) and project.
  // Gauss-Seidel: a joint's parts are corrected one after another (orientation, then the anchors,
  // whose lever arms turn the bodies again), so one projection more than halves the violation and
  // twenty cut it by 50 or more (geometric convergence; slowest, factor 0.79 per pass, for a hinge
  // to the world with its anchor half a box away from the centre); a wrong sign, lever arm or
  // effective mass does neither.
  // Direct (joint_tree.hpp): one call re-linearises until |C| < 1e-9, i.e. Newton's method, which
  // from 1e-3 reaches it in two or three solves; a wrong Jacobian would stall at its first-order
  // error (~1e-6) and hit the pass limit. Prismatic joints are not in the tree and keep Gauss-Seidel.
  const std::vector<std::string> joints = {
      R"({"name": "j", "type": "fixed", "bodies": ["a", "b"], "anchor": [0.5, 0, 0]})",
      R"({"name": "j", "type": "spherical", "bodies": ["a", "b"], "anchor": [0.5, 0, 0]})",
      R"({"name": "j", "type": "hinge", "bodies": ["a", "b"], "anchor": [0.5, 0, 0], "axis": [0, 1, 1]})",
      R"({"name": "j", "type": "prismatic", "bodies": ["a", "b"], "anchor": [0.5, 0, 0], "axis": [1, 1, 0]})",
      R"({"name": "j", "type": "distance", "bodies": ["a", "b"], "anchors": [[0.3, 0.1, 0], [0.8, 0, 0.1]]})",
      R"({"name": "j", "type": "hinge", "bodies": ["world", "b"], "anchor": [0.5, 0, 0], "axis": [0, 0, 1]})"};
  for (const bool direct : {false, true}) {
    for (const std::string& j : joints) {
      Scene s = two_boxes(j, direct ? "direct" : "gauss_seidel");
      const Index b = s.model.objects[s.model.find_object("b")].body;
      s.state.rigid.position[b] += Vec3(1e-3, -0.7e-3, 0.5e-3);
      s.state.rigid.orientation[b] =
          (Quat(Eigen::AngleAxisd(1.2e-3, Vec3(0.3, -1, 0.4).normalized())) * s.state.rigid.orientation[b]).normalized();
      const JointError before = joint_error(s.model.joints[0], s.state);
      const Real h = 1.0 / 1200;
      Real drive_start = 0;
      reset_joints(s.model, s.state, &drive_start);
      const int solves = solve_joint_forest(s.model, s.state, SubstepStart{}, h);
      project_joints(s.model, s.state, &drive_start, SubstepStart{}, h);
      const JointError once = joint_error(s.model.joints[0], s.state);
      for (int k = 0; k < 19; ++k) project_joints(s.model, s.state, &drive_start, SubstepStart{}, h);
      const JointError after = joint_error(s.model.joints[0], s.state);
      const std::string what = j + (direct ? " direct" : " gauss_seidel");
      EXPECT_GT(before.position + before.angle, 5e-4) << what;
      if (s.model.joint_forest.in_tree(0)) {
        EXPECT_LE(solves, 3) << what;
        EXPECT_LT(once.position + once.angle, 1e-8) << what;
      } else {
        EXPECT_EQ(solves, 0) << what;
        EXPECT_LT(once.position + once.angle, 0.5 * (before.position + before.angle)) << what;
        EXPECT_LT(after.position + after.angle, 0.02 * (before.position + before.angle)) << what;
      }
      EXPECT_EQ(s.model.joint_forest.in_tree(0), direct && j.find("prismatic") == std::string::npos) << what;
    }
  }
}

TEST(RigidJoints, CompliantDistanceJointStretchesByComplianceTimesForce) {
  // Mueller 2020's test: a 1 kg and a 1/8 kg box hang in series from distance joints with
  // alpha = 0.01 m/N and g = 10: the upper joint carries 11.25 N and stretches 0.1125 m, the
  // lower 1.25 N and 0.0125 m, whatever the substep count (XPBD's compliance is in SI units).
  for (int substeps : {5, 40}) {
    Scene s = scene_from_json(fmt::format(R"({{"name": "hang", "settings": {{"substeps": {}, "gravity": [0, -10, 0]}},
      "objects": [{{"name": "big", "kind": "rigid_body", "shape": {{"type": "box", "half_extents": [0.1, 0.1, 0.1]}}, "position": [0, -1, 0], "mass": 1}},
                  {{"name": "small", "kind": "rigid_body", "shape": {{"type": "box", "half_extents": [0.05, 0.05, 0.05]}}, "position": [0, -2, 0], "mass": 0.125}}],
      "joints": [{{"name": "upper", "type": "distance", "bodies": ["world", "big"], "anchors": [[0, 0, 0], [0, -0.9, 0]], "compliance": 0.01, "damping": 5}},
                 {{"name": "lower", "type": "distance", "bodies": ["big", "small"], "anchors": [[0, -1.1, 0], [0, -1.95, 0]], "compliance": 0.01, "damping": 5}}]}})",
                                          substeps));
    run_steps(s, 600);
    const Index big = s.model.objects[s.model.find_object("big")].body;
    const Index small = s.model.objects[s.model.find_object("small")].body;
    // Rest lengths 0.9 and 0.85 m between the anchors (box centres 0.1 and 0.05 below them).
    EXPECT_NEAR(-s.state.rigid.position[big].y() - 1.0, 0.1125, 2e-3) << substeps << " substeps";
    EXPECT_NEAR(s.state.rigid.position[big].y() - s.state.rigid.position[small].y() - 1.0, 0.0125, 5e-4)
        << substeps << " substeps";
  }
}

TEST(RigidJoints, HingeLimitAndVelocityDrive) {
  // A door (1 x 2 m plate) on a vertical hinge driven at 1 rad/s with ample torque turns at
  // 1 rad/s (to 1e-5) and stops at its 90 degree limit. Its angle lags the drive by 1.3 % at
  // 0.5 s: each substep the anchor correction after the drive turns the door back a little.
  Scene s = scene_from_json(R"({"name": "door", "settings": {"gravity": [0, 0, 0]},
    "objects": [{"name": "door", "kind": "rigid_body", "shape": {"type": "box", "half_extents": [0.5, 1, 0.02]}, "position": [0.5, 1, 0], "density": 500}],
    "joints": [{"name": "h", "type": "hinge", "bodies": ["world", "door"], "anchor": [0, 1, 0], "axis": [0, 1, 0],
                "limits_deg": [-90, 90], "drive": {"target_velocity": 1.0, "max_torque": 1000}}]})");
  run_steps(s, 30);  // 0.5 s
  const Index b = 0;
  EXPECT_NEAR(s.state.rigid.angular_velocity[b].y(), 1.0, 1e-5);
  EXPECT_NEAR(joint_coordinate(s.model.joints[0], s.state), 0.5, 0.02 * 0.5);
  run_steps(s, 90);  // 2 s in all: the limit holds at pi/2
  EXPECT_NEAR(joint_coordinate(s.model.joints[0], s.state), kPi / 2, 1e-6);
  EXPECT_LT(joint_error(s.model.joints[0], s.state).position, 1e-9);
}

TEST(RigidJoints, DriveTorqueIsLimited) {
  // The same door driven with a 1 N m limit accelerates at tau / I about the hinge:
  // I = m (w^2 / 3 + t^2 / 12) for a plate of width w = 1 m hinged at its edge. 1 %: the drive
  // reaches its limit only in the first substep's iterations (the start lags by one substep of
  // 1/1200 s in 0.5 s, 0.2 %).
  Scene s = scene_from_json(R"({"name": "door", "settings": {"gravity": [0, 0, 0]},
    "objects": [{"name": "door", "kind": "rigid_body", "shape": {"type": "box", "half_extents": [0.5, 1, 0.02]}, "position": [0.5, 1, 0], "density": 500}],
    "joints": [{"name": "h", "type": "hinge", "bodies": ["world", "door"], "anchor": [0, 1, 0], "axis": [0, 1, 0],
                "drive": {"target_velocity": 10.0, "max_torque": 1}}]})");
  const Real m = s.model.rigid.body_mass[0];
  const Real inertia = m * (1.0 / 3 + 0.04 * 0.04 / 12);
  run_steps(s, 30);
  EXPECT_NEAR(s.state.rigid.angular_velocity[0].y(), 0.5 / inertia, 0.01 * 0.5 / inertia);
}

TEST(RigidJoints, SphericalTwistLimitStopsASpinAndIsMeasured) {
  // A box spinning at 2 rad/s about a spherical joint's axis (x, through its centre) with twist
  // limits of +-30 degrees: free it would turn 2 rad in 1 s; limited it stops at 30 degrees (the
  // limit is rigid: to 1e-6 rad) and joint_error reports no violation. Turned by hand to 40
  // degrees, joint_error reports the 10 degree excess exactly (the twist is measured about the
  // mean of the two axes, here both x).
  Scene s = scene_from_json(R"({"name": "twist", "settings": {"gravity": [0, 0, 0]},
    "objects": [{"name": "b", "kind": "rigid_body", "shape": {"type": "box", "half_extents": [0.5, 0.2, 0.1]},
                 "position": [0, 0, 0], "angular_velocity": [2, 0, 0]}],
    "joints": [{"name": "j", "type": "spherical", "bodies": ["world", "b"], "anchor": [0, 0, 0], "axis": [1, 0, 0],
                "swing_deg": 20, "twist_deg": [-30, 30]}]})");
  run_steps(s, 60);
  const Eigen::AngleAxisd turned(s.state.rigid.orientation[0]);
  EXPECT_NEAR(turned.angle(), kPi / 6, 1e-6);
  EXPECT_NEAR(std::abs(turned.axis().x()), 1.0, 1e-9);
  EXPECT_LT(joint_error(s.model.joints[0], s.state).angle, 1e-6);
  s.state.rigid.orientation[0] = Quat(Eigen::AngleAxisd(40 * kPi / 180, Vec3::UnitX()));
  EXPECT_NEAR(joint_error(s.model.joints[0], s.state).angle, 10 * kPi / 180, 1e-12);
}

TEST(RigidJoints, ResultsAreBitIdenticalOnOneAndTwoThreads) {
  const std::string scene = R"({"name": "pile", "settings": {"threads": THREADS},
    "objects": [{"name": "ground", "kind": "collider", "shape": {"type": "plane"}},
      {"name": "a", "kind": "rigid_body", "shape": {"type": "box", "half_extents": [0.2, 0.2, 0.2]}, "position": [0, 0.3, 0], "rotation_deg": [5, 10, 0]},
      {"name": "b", "kind": "rigid_body", "shape": {"type": "sphere", "radius": 0.15}, "position": [0.1, 0.9, 0]},
      {"name": "c", "kind": "rigid_body", "shape": {"type": "capsule", "radius": 0.1, "half_height": 0.2}, "position": [-0.1, 1.4, 0.1], "rotation_deg": [0, 0, 70]},
      {"name": "d", "kind": "rigid_body", "shape": {"type": "cylinder", "radius": 0.15, "half_height": 0.1}, "position": [0, 1.9, 0], "rotation_deg": [30, 0, 0]}],
    "joints": [{"name": "j", "type": "spherical", "bodies": ["world", "d"], "anchors": [[0, 2.5, 0], [0, 2.0, 0]]}]})";
  auto run = [&](int threads) {
    std::string text = scene;
    text.replace(text.find("THREADS"), 7, std::to_string(threads));
    Scene s = scene_from_json(text);
    run_steps(s, 90);
    return s.state.rigid;
  };
  const RigidBodyState one = run(1), two = run(2);
  for (size_t b = 0; b < one.position.size(); ++b) {
    EXPECT_EQ(one.position[b], two.position[b]);
    EXPECT_EQ(one.orientation[b].coeffs(), two.orientation[b].coeffs());
  }
}

}  // namespace
}  // namespace moreau
