// The velocity-level formulation (solvers/nmd/) against the closed forms of its own equations
// and of the mechanics it simulates: SPOOK's relaxation of a hard constraint, the elongation of
// compliant links, Coulomb friction on an incline, restitution and a torque-bounded motor.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <cmath>

#include "moreau/constraints/joints/joint.hpp"
#include "moreau/world.hpp"
#include "test_helpers.hpp"

namespace moreau {
namespace {

using test::run_steps;
using test::scene_from_json;

Index body_of(const Scene& s, const std::string& name) { return s.model.objects[s.model.find_object(name)].body; }

// SPOOK (Lacoursiere 2007): a hard row (eps = 0) with d = tau/h satisfies
//   w_{n+1} = -a g_n + b w_n,  g_{n+1} = g_n + h w_{n+1},  a = 4/(h(1+4d)), b = 1/(1+4d),
// w = dC/dt. A ball on a spherical joint at its centre, started at 1 m/s with no gravity, follows
// this recurrence exactly (one block, solved whole): compare step by step to round-off.
const char* const kMethods[] = {"pgs", "direct", "hybrid"};

TEST(NmdBasics, HardConstraintRelaxesAsTheSpookRecurrence) {
  for (const char* method : kMethods)
  for (const Real d : {0.5, 2.0, 5.0}) {
    const Real h = 0.01;
    Scene s = scene_from_json(fmt::format(R"({{"name": "relax",
      "settings": {{"solver": "nmd", "dt": {}, "gravity": [0, 0, 0], "nmd": {{"stabilization": {}, "method": "{}"}}}},
      "objects": [{{"name": "ball", "kind": "rigid_body", "shape": {{"type": "sphere", "radius": 0.1}},
                   "position": [0, 0, 0], "velocity": [1, 0, 0]}}],
      "joints": [{{"name": "pin", "type": "spherical", "bodies": ["world", "ball"], "anchor": [0, 0, 0]}}]}})",
                                          h, d, method));
    const Index b = body_of(s, "ball");
    const Real a = 4 / (h * (1 + 4 * d)), bb = 1 / (1 + 4 * d);
    Real g = 0, w = 1;
    for (int n = 0; n < 20; ++n) {
      run_steps(s, 1);
      w = -a * g + bb * w;
      g += h * w;
      EXPECT_NEAR(s.state.rigid.position[b].x(), g, 1e-12) << method << ", d = " << d << ", step " << n + 1;
    }
  }
}

TEST(NmdBasics, SpookWithTwoStepsIsCriticallyDamped) {
  // d = 2: the recurrence's eigenvalues are both 1/3, so the offset never changes sign.
  Scene s = scene_from_json(R"({"name": "relax", "settings": {"solver": "nmd", "gravity": [0, 0, 0]},
    "objects": [{"name": "ball", "kind": "rigid_body", "shape": {"type": "sphere", "radius": 0.1},
                 "position": [0, 0, 0], "velocity": [1, 0, 0]}],
    "joints": [{"name": "pin", "type": "spherical", "bodies": ["world", "ball"], "anchor": [0, 0, 0]}]})");
  const Index b = body_of(s, "ball");
  for (int n = 0; n < 40; ++n) {
    run_steps(s, 1);
    EXPECT_GE(s.state.rigid.position[b].x(), 0) << "step " << n + 1;
  }
}

// A chain of five 1 kg balls hanging from the world on spherical joints of compliance eps: joint k
// carries the weight of the balls below it, (5 - k) m g, and stretches by eps times that.
// At rest SPOOK's row reads S l = -a g, i.e. eps f = -g exactly; what is left is the solver's
// convergence, which warm starting over 2 s brings below 1e-6 relative.
TEST(NmdBasics, CompliantLinksStretchByComplianceTimesTension) {
  for (const char* method : kMethods) {
  const Real eps = 1e-4, m = 1, g = 9.81, r = 0.05;
  std::string objects, joints;
  for (int k = 0; k < 5; ++k) {
    objects += fmt::format(R"({}{{"name": "ball{}", "kind": "rigid_body", "shape": {{"type": "sphere", "radius": {}}},
      "mass": {}, "position": [0, {}, 0]}})",
                           k ? "," : "", k, r, m, -(2 * k + 1) * r);
    joints += fmt::format(R"({}{{"name": "link{}", "type": "spherical", "bodies": ["{}", "ball{}"],
      "anchor": [0, {}, 0], "compliance": {}}})",
                          k ? "," : "", k, k ? fmt::format("ball{}", k - 1) : "world", k, -2 * k * r, eps);
  }
  Scene s = scene_from_json(fmt::format(R"({{"name": "chain", "settings": {{"solver": "nmd",
    "nmd": {{"iterations": 100, "method": "{}"}}}}, "objects": [{}], "joints": [{}]}})",
                                        method, objects, joints));
  run_steps(s, 120);
  for (int k = 0; k < 5; ++k) {
    const Real expected = eps * (5 - k) * m * g;
    const Real stretch = joint_error(s.model.joints[k], s.state).position;
    EXPECT_NEAR(stretch, expected, 1e-6 * expected) << method << ", link " << k;
  }
  }
}

// The benchmark chain: 100 links of 0.1 kg on ball joints holding 100 kg (mass ratio 1:1000).
// The direct and hybrid methods solve the joints' rows exactly each step: the chain's stretch
// stays below 0.01 % of its 10 m. Projected Gauss-Seidel does not converge at this mass ratio
// (the chain stretches by metres and the run fails; docs/validation.md).
TEST(NmdBasics, HundredLinkChainHoldsAThousandTimesItsLinkMass) {
  for (const char* method : {"direct", "hybrid"}) {
    World world = World::load(std::string(MOREAU_SOURCE_DIR) + "/bench/scenes/chain_100_hanging.json",
                              {"settings.solver=\"nmd\"", fmt::format("settings.nmd.method=\"{}\"", method)});
    Real largest = 0;
    for (int step = 0; step < 300; ++step) {
      world.step(1);
      const std::vector<double> probes = world.probe_values();
      largest = std::max(largest, probes.at(3));  // joints.position: the largest joint gap (m)
    }
    const std::vector<std::string> names = world.probe_names();
    ASSERT_EQ(names.at(3), "joints.position");
    EXPECT_LT(100 * largest, 1e-4 * 10) << method;
    std::printf("nmd %s, 100-link chain holding 100 kg: largest joint gap %.2e m (chain stretch below %.1e of 10 m)\n",
                method, largest, 100 * largest / 10);
  }
}

}  // namespace
}  // namespace moreau

namespace moreau {
namespace {

// A 0.5 m box on a slope tilted by theta = 30 degrees about world x and turned by psi about the
// vertical, the box turned by beta about the slope's normal: as a collider slope or as a fixed
// rigid-body slope. Returns the box's acceleration along the downhill direction over the second
// second (symplectic Euler integrates a constant acceleration's velocity exactly) and its largest
// distance from the downhill line through its start.
struct InclineRun {
  Real downhill_acceleration = 0, sideways = 0, distance = 0;
  Real second_second = 0;  // distance moved over the second second
};

InclineRun run_incline(Real mu_s, Real mu_k, Real psi_deg, Real beta_deg, bool rigid_slope, const std::string& method) {
  const Real theta = kPi / 6, psi = psi_deg * kPi / 180, beta = beta_deg * kPi / 180;
  const Quat slope = Quat(Eigen::AngleAxisd(psi, Vec3::UnitY())) * Quat(Eigen::AngleAxisd(theta, Vec3::UnitX()));
  const Vec3 n = slope * Vec3::UnitY();
  const Quat box = slope * Quat(Eigen::AngleAxisd(beta, Vec3::UnitY()));
  const Vec3 center = 0.75 * n;
  const std::string material = fmt::format(R"({{"static": {}, "dynamic": {}}})", mu_s, mu_k);
  const std::string slope_object =
      rigid_slope
          ? fmt::format(R"({{"name": "slope", "kind": "rigid_body", "fixed": true, "friction": {},
              "shape": {{"type": "box", "half_extents": [10, 0.5, 10]}}, "position": [0, 0, 0],
              "orientation": [{}, {}, {}, {}]}})",
                        material, slope.w(), slope.x(), slope.y(), slope.z())
          : fmt::format(R"({{"name": "slope", "kind": "collider", "friction": {},
              "shape": {{"type": "box", "center": [0, 0, 0], "half_extents": [10, 0.5, 10], "rotation_deg": [30, {}, 0]}}}})",
                        material, psi_deg);
  Scene s = scene_from_json(fmt::format(R"({{"name": "incline", "settings": {{"solver": "nmd", "nmd": {{"method": "{}"}}}},
    "objects": [{}, {{"name": "box", "kind": "rigid_body", "shape": {{"type": "box", "half_extents": [0.25, 0.25, 0.25]}},
      "position": [{}, {}, {}], "orientation": [{}, {}, {}, {}], "density": 1000, "friction": {}}}]}})",
                                        method, slope_object, center.x(), center.y(), center.z(), box.w(), box.x(),
                                        box.y(), box.z(), material));
  const Index b = body_of(s, "box");
  const Vec3 start = s.state.rigid.position[b];
  const Vec3 downhill = (-Vec3::UnitY() - (-Vec3::UnitY()).dot(n) * n).normalized();
  InclineRun result;
  run_steps(s, 60);
  const Real v1 = s.state.rigid.velocity[b].dot(downhill);
  const Vec3 after_one_second = s.state.rigid.position[b];
  run_steps(s, 60);
  result.second_second = (s.state.rigid.position[b] - after_one_second).norm();
  const Real v2 = s.state.rigid.velocity[b].dot(downhill);
  result.downhill_acceleration = v2 - v1;
  const Vec3 moved = s.state.rigid.position[b] - start;
  result.distance = moved.norm();
  result.sideways = (moved - moved.dot(downhill) * downhill).norm();
  return result;
}

TEST(NmdFriction, BoxSlidesAtTheKineticCoulombAccelerationForEveryOrientation) {
  // mu_s = 0.5 < tan 30 = 0.577 and mu_k = 0.3: a = g (sin 30 - 0.3 cos 30) = 2.3562 m/s^2.
  // mu_s = 0.57 sits just below tan 30: the box slides too, at the same kinetic acceleration.
  const Real expected = 9.81 * (0.5 - 0.3 * std::cos(kPi / 6));
  for (const char* method : kMethods) {
  Real worst = 0, worst_sideways = 0;
  for (const Real mu_s : {0.5, 0.57})
    for (const bool rigid_slope : {false, true})
      for (const Real psi : {0.0, 37.0, 90.0})
        for (const Real beta : {0.0, 30.0, 45.0}) {
          const InclineRun r = run_incline(mu_s, 0.3, psi, beta, rigid_slope, method);
          EXPECT_NEAR(r.downhill_acceleration, expected, 0.01 * expected)
              << method << ", " << (rigid_slope ? "rigid" : "collider") << " slope, mu_s " << mu_s << ", psi " << psi
              << ", beta " << beta;
          EXPECT_LT(r.sideways, 1e-3 * r.distance)
              << method << ", mu_s " << mu_s << ", psi " << psi << ", beta " << beta;
          worst = std::max(worst, std::abs(r.downhill_acceleration / expected - 1));
          worst_sideways = std::max(worst_sideways, r.sideways / r.distance);
        }
  std::printf("nmd %s, incline in 36 orientations: acceleration within %.2e of g (sin - mu_k cos), sideways %.1e of the path\n",
              method, worst, worst_sideways);
  }
}

TEST(NmdFriction, BoxSticksWhenTheSlopeIsWithinTheStaticCone) {
  // tan 30 = 0.577 <= mu_s: the box stays, whatever mu_k. It settles into the slope over the first
  // steps (SPOOK lets a hard row relax over d = 2 steps; measured up to 27 micrometres), then does not
  // move: over the second second by round-off only.
  for (const char* method : kMethods) {
    Real farthest = 0, latest = 0;
    for (const Real mu_s : {0.58, 0.6, 0.7})
      for (const bool rigid_slope : {false, true})
        for (const Real beta : {0.0, 45.0}) {
          const InclineRun r = run_incline(mu_s, 0.3, 37.0, beta, rigid_slope, method);
          EXPECT_LT(r.distance, 1e-4) << method << ", mu_s " << mu_s << (rigid_slope ? " rigid" : " collider") << " beta " << beta;
          EXPECT_LT(r.second_second, 1e-9) << method << ", mu_s " << mu_s << (rigid_slope ? " rigid" : " collider")
                                           << " beta " << beta;
          farthest = std::max(farthest, r.distance);
          latest = std::max(latest, r.second_second);
        }
    std::printf("nmd %s, incline, mu_s >= 0.58 > tan 30: the box moved at most %.2e m in 2 s, %.1e m in the second\n",
                method, farthest, latest);
  }
}

}  // namespace
}  // namespace moreau

namespace moreau {
namespace {

// Apex heights of a 0.1 m ball dropped from 1 m onto a plane, both with restitution e = 0.5.
std::vector<Real> bounce_apexes(Real dt, int substeps) {
  Scene s = scene_from_json(fmt::format(R"({{"name": "bounce", "settings": {{"solver": "nmd", "dt": {}, "nmd": {{"substeps": {}}}}},
    "objects": [{{"name": "ground", "kind": "collider", "shape": {{"type": "plane"}}, "restitution": 0.5}},
                {{"name": "ball", "kind": "rigid_body", "shape": {{"type": "sphere", "radius": 0.1}},
                 "position": [0, 1.1, 0], "restitution": 0.5}}]}})",
                                        dt, substeps));
  const Index b = body_of(s, "ball");
  std::vector<Real> apex;
  Real previous_vy = 0;
  for (int step = 0; step < static_cast<int>(1.6 / dt); ++step) {
    run_steps(s, 1);
    const Real vy = s.state.rigid.velocity[b].y();
    if (previous_vy > 0 && vy <= 0) apex.push_back(s.state.rigid.position[b].y() - 0.1);
    previous_vy = vy;
  }
  return apex;
}

TEST(NmdContacts, BallBouncesToRestitutionSquaredTimesTheDropHeight) {
  // Rebound apexes e^2 h = 0.25 m and e^4 h = 0.0625 m. The impact falls inside a solve: the ball
  // turns at its gap g above the plane (g < h |v|), which lowers the apex by (1 - e^2) g; and the
  // apex is sampled at step ends, g dt^2 / 2 low at most. With dt = 1/600 s and h = dt/10 both
  // stay below 0.5 % of the second apex.
  const std::vector<Real> apex = bounce_apexes(1.0 / 600, 10);
  ASSERT_GE(apex.size(), 2u);
  EXPECT_NEAR(apex[0], 0.25, 0.01 * 0.25);
  EXPECT_NEAR(apex[1], 0.0625, 0.01 * 0.0625);
  std::printf("nmd bounce, e = 0.5 from 1 m, h = 1/6000 s: apexes %.5f m and %.5f m (exact 0.25 and 0.0625)\n", apex[0],
              apex[1]);
}

// A 1 kg, 1 m arm on a hinge about z through its end, driven at 2 rad/s with a bounded torque
// against gravity (at most m g L/2 = 4.905 N m).
struct MotorRun {
  Real slowest = 1e9, fastest = -1e9;   // rad/s after the first second
  Real largest_torque = 0;              // N m, over the run
  Real final_torque = 0;
};

MotorRun run_motor(Real max_torque, const char* method) {
  Scene s = scene_from_json(fmt::format(R"({{"name": "motor", "settings": {{"solver": "nmd", "nmd": {{"method": "{}"}}}},
    "objects": [{{"name": "arm", "kind": "rigid_body", "shape": {{"type": "box", "half_extents": [0.5, 0.02, 0.02]}},
                 "position": [0.5, 0, 0], "mass": 1}}],
    "joints": [{{"name": "shoulder", "type": "hinge", "bodies": ["world", "arm"], "anchor": [0, 0, 0], "axis": [0, 0, 1],
                "drive": {{"target_velocity": 2, "max_torque": {}}}}}]}})",
                                        method, max_torque));
  const Index b = body_of(s, "arm");
  const Real h = s.model.settings.dt;
  MotorRun run;
  for (int step = 0; step < 240; ++step) {
    run_steps(s, 1);
    const Real torque = std::abs(s.state.joint_lambda[0][JointSlot::drive]) / (h * h);
    run.largest_torque = std::max(run.largest_torque, torque);
    run.final_torque = torque;
    if (step >= 60) {
      const Real w = s.state.rigid.angular_velocity[b].z();
      run.slowest = std::min(run.slowest, w);
      run.fastest = std::max(run.fastest, w);
    }
  }
  return run;
}

TEST(NmdJoints, MotorisedHingeHoldsItsTargetVelocityUnderLoadWithinItsTorque) {
  for (const char* method : kMethods) {
    // 10 N m beats gravity everywhere: the arm turns at 2 rad/s within 1 %, the torque within 10 N m.
    const MotorRun strong = run_motor(10, method);
    EXPECT_NEAR(strong.slowest, 2, 0.02) << method;
    EXPECT_NEAR(strong.fastest, 2, 0.02) << method;
    EXPECT_LE(strong.largest_torque, 10 * (1 + 1e-12)) << method;
    // 3 N m cannot lift it past m g L/2 cos(phi) = 3: it swings below, the motor pushing with
    // exactly its bound while slower than 2 rad/s and braking at it while gravity would speed it up.
    const MotorRun weak = run_motor(3, method);
    EXPECT_LE(weak.largest_torque, 3 * (1 + 1e-12)) << method;
    EXPECT_NEAR(weak.final_torque, 3, 1e-9) << method;
    EXPECT_LT(weak.fastest, 2 * 1.01) << method;
    std::printf("nmd %s, motor at 2 rad/s: %.6f..%.6f rad/s with 10 N m (peak %.4f N m); %.6f N m at the end with 3 N m\n",
                method, strong.slowest, strong.fastest, strong.largest_torque, weak.final_torque);
  }
}

// A joint's dampers under nmd are implicit dampers of decay rate c against the ends' effective
// mass (nmd_system.hpp): alone on a free coordinate, the velocity is divided by 1 + c h per step.
// A wheel hinged at its centre (its inertia about the hinge is its own) spins down from 3 rad/s
// and a block on a slider through its centre slides down from 1.5 m/s, c = 2/s, h = 1/60 s, no
// gravity: after n steps the speed is v0 / (1 + c h)^n, within the solve's tolerance (1e-9 for
// the factored methods, 1e-6 for pgs's iterations), and exp(-c t) to first order in c h.
TEST(NmdJoints, JointDampersDivideTheirFreeVelocityByOnePlusRateTimesStep) {
  for (const char* method : kMethods) {
    Scene s = scene_from_json(fmt::format(R"({{"name": "dampers", "settings": {{"solver": "nmd", "dt": {},
        "gravity": [0, 0, 0], "nmd": {{"method": "{}"}}}},
      "objects": [{{"name": "wheel", "kind": "rigid_body", "shape": {{"type": "box", "half_extents": [0.3, 0.3, 0.05]}},
                   "position": [0, 0, 0], "mass": 2, "angular_velocity": [0, 0, 3]}},
                  {{"name": "block", "kind": "rigid_body", "shape": {{"type": "box", "half_extents": [0.1, 0.2, 0.3]}},
                   "position": [0, 2, 0], "mass": 5, "velocity": [1.5, 0, 0]}}],
      "joints": [{{"name": "axle", "type": "hinge", "bodies": ["world", "wheel"], "anchor": [0, 0, 0], "axis": [0, 0, 1],
                   "angular_damping": 2}},
                 {{"name": "rail", "type": "prismatic", "bodies": ["world", "block"], "anchor": [0, 2, 0], "axis": [1, 0, 0],
                   "damping": 2}}]}})",
                                          1.0 / 60, method));
    const Index wheel = body_of(s, "wheel"), block = body_of(s, "block");
    const Real h = 1.0 / 60, decay = 1 + 2 * h;
    const Real tolerance = std::string(method) == "pgs" ? 1e-6 : 1e-9;
    for (int step = 1; step <= 60; ++step) {
      run_steps(s, 1);
      const Real expected = std::pow(decay, -step);
      ASSERT_NEAR(s.state.rigid.angular_velocity[wheel].z() / 3, expected, tolerance) << method << " step " << step;
      ASSERT_NEAR(s.state.rigid.velocity[block].x() / 1.5, expected, tolerance) << method << " step " << step;
    }
    // After 1 s (c t = 2): (1 + 1/30)^-60 = 0.1398 against exp(-2) = 0.1353, 3.3 % above (the
    // implicit damper's per-step factor is exp(-c h) (1 + (c h)^2 / 2 + ...)).
    EXPECT_NEAR(s.state.rigid.angular_velocity[wheel].z() / 3, std::exp(-2.0), 0.04 * std::exp(-2.0)) << method;
    std::printf("nmd %s joint dampers after 1 s: wheel %.6f, slider %.6f of their start; 1/(1 + c h)^60 = %.6f, exp(-c t) = %.6f\n",
                method, s.state.rigid.angular_velocity[wheel].z() / 3, s.state.rigid.velocity[block].x() / 1.5,
                std::pow(decay, -60), std::exp(-2.0));
  }
}

}  // namespace
}  // namespace moreau
