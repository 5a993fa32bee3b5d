// Grains turn as solid spheres: friction acts at the contact point and rolling resistance brakes
// the turning, under xpbd against colliders and other particles, under nmd against everything
// (rigid bodies too). A grain on an incline (gravity tilted by theta over the ground) has the
// textbook accelerations of a sphere, and two grains that meet off-centre keep their momentum and
// angular momentum, spin included.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <cmath>
#include <string>
#include <vector>

#include "moreau/math/types.hpp"
#include "moreau/world.hpp"

namespace moreau {
namespace {

constexpr Real kG = 9.81;
constexpr const char* kXpbd = R"("dt": 0.005, "substeps": 10)";
constexpr const char* kNmd = R"("solver": "nmd", "dt": 0.005)";
constexpr const char* kColliderGround = R"({{"name": "ground", "kind": "collider", "shape": {{"type": "plane"}}, "friction": {}}})";
constexpr const char* kBodyGround =
    R"({{"name": "ground", "kind": "rigid_body", "fixed": true, "shape": {{"type": "box", "size": [4, 0.2, 4]}},
        "position": [0, -0.1, 0], "friction": {}}})";

// The acceleration down an incline of `degrees` of a 5 mm grain with friction mu (grain and
// ground) and rolling resistance mu_r: the slope of its velocity over [0.25, 0.5] s.
Real incline_acceleration(Real degrees, Real mu, Real mu_r, const char* solver = kXpbd,
                          const char* ground = kColliderGround) {
  const Real theta = degrees * kPi / 180;
  World w = World::from_json(fmt::format(
      R"({{"name": "incline", "settings": {{{}, "duration": 1, "gravity": [{}, {}, 0]}},
      "objects": [{},
                  {{"name": "grain", "kind": "granular", "blocks": [{{"min": [0, 0, 0], "max": [0.01, 0.01, 0.01]}}],
                    "radius": 0.005, "friction": {}, "rolling_resistance": {}}}],
      "probes": [{{"name": "v", "type": "point", "object": "grain", "vertex": 0, "quantity": "velocity"}}]}})",
      solver, kG * std::sin(theta), -kG * std::cos(theta), fmt::format(fmt::runtime(ground), mu), mu, mu_r));
  Real v_early = 0;
  while (w.time() < 0.5 - 1e-9) {
    w.step();
    if (std::abs(w.time() - 0.25) < 1e-9) v_early = w.probe_values()[0];
  }
  return (w.probe_values()[0] - v_early) / 0.25;
}

struct InclineCase {
  Real degrees, mu, mu_r, expected;
  const char* what;
};

// Rolling without slipping (mu = 1 >= tan(theta) / 3.5): a = 5/7 g sin(theta). Sliding (mu =
// 0.05 < tan(theta) / 3.5 = 0.104): a = g (sin - mu cos). Rolling against resistance
// (mu_r < tan(theta)): the torque mu_r r N about the centre gives a = 5/7 g (sin - mu_r cos).
// At rest when mu_r > tan(theta). One contact's friction is solved exactly every substep (the
// stick impulses cancel slip and roll together), so the only error is rounding: 1e-6 of g.
std::vector<InclineCase> incline_cases() {
  auto s = [](Real degrees) { return std::sin(degrees * kPi / 180); };
  auto c = [](Real degrees) { return std::cos(degrees * kPi / 180); };
  return {
      {20, 1.0, 0.0, 5.0 / 7 * kG * s(20), "rolls"},
      {20, 0.05, 0.0, kG * (s(20) - 0.05 * c(20)), "slides"},
      {20, 1.0, 0.3, 5.0 / 7 * kG * (s(20) - 0.3 * c(20)), "rolls against mu_r 0.3"},
      {30, 1.0, 0.5, 5.0 / 7 * kG * (s(30) - 0.5 * c(30)), "rolls against mu_r 0.5"},
      {20, 1.0, 0.5, 0.0, "rests (mu_r 0.5 > tan 20 = 0.364)"},
      {30, 1.0, 0.6, 0.0, "rests (mu_r 0.6 > tan 30 = 0.577)"},
  };
}

TEST(GrainRolling, AGrainOnAnInclineRollsSlidesOrRestsAsASphereDoes) {
  for (const InclineCase& k : incline_cases()) {
    const Real a = incline_acceleration(k.degrees, k.mu, k.mu_r);
    std::printf("incline %.0f deg, mu %.2f, mu_r %.1f: %s, a = %.6f m/s^2 (expected %.6f)\n", k.degrees, k.mu, k.mu_r,
                k.what, a, k.expected);
    EXPECT_NEAR(a, k.expected, 1e-6 * kG) << k.what;
  }
}

// The same under nmd, on a collider and on a fixed rigid body: the velocity-level solve of the one
// contact (normal, friction and turning rows) converges within its sweeps. On the collider the
// accelerations come out to rounding (measured: 2e-15 of g; 1e-9 of g leaves room for the order of
// additions). On the body the grain's lever is its distance to the body's surface, and the grain
// rests 1.3e-9 m deep in it by the contact compliance (1e-7 m/N times its weight): a lever
// 2.5e-7 of r short, which moves the rolling cases by up to 8e-8 of g (measured); 1e-6 of g.
TEST(GrainRolling, UnderNmdAGrainOnAColliderOrARigidBodyRollsSlidesOrRestsAsASphereDoes) {
  for (const char* ground : {kColliderGround, kBodyGround})
    for (const InclineCase& k : incline_cases()) {
      const Real a = incline_acceleration(k.degrees, k.mu, k.mu_r, kNmd, ground);
      std::printf("nmd, on a %s: incline %.0f deg, mu %.2f, mu_r %.1f: %s, a = %.9f m/s^2 (expected %.9f)\n",
                  ground == kBodyGround ? "rigid body" : "collider", k.degrees, k.mu, k.mu_r, k.what, a, k.expected);
      EXPECT_NEAR(a, k.expected, (ground == kBodyGround ? 1e-6 : 1e-9) * kG) << k.what;
    }
}

// Two 5 mm grains meet off-centre (4 mm apart across their paths) at 1 m/s each, without gravity,
// with restitution 0.5, and with or without friction (0.5, rolling resistance 0.1). Linear
// momentum stays zero to rounding. Angular momentum (orbit and spin): the impulses act at one
// contact point that splits the centre distance by the radii, so they exert no net torque; but a
// position-level step measures velocities as (x - x_start) / h while the normal turns within the
// substep, which changes L by O(h |v_rel| / d) (1.5 % at h = 0.25 ms here, without friction
// too): the change shrinks in proportion to h. Friction sets the grains spinning and takes energy.
struct Meeting {
  Real momentum, angular_change, energy_before, energy_after;  // kg m/s, relative, J
};

Meeting off_centre_meeting(Real mu, int substeps, const char* solver = "xpbd") {
  World w = World::from_json(fmt::format(
      R"({{"name": "glancing", "settings": {{"solver": "{2}", "dt": 0.001, "substeps": {1}, "duration": 0.1, "gravity": [0, 0, 0]}},
      "objects": [{{"name": "left", "kind": "granular", "blocks": [{{"min": [-0.03, 0.004, 0], "max": [-0.02, 0.014, 0.01]}}],
                   "radius": 0.005, "friction": {0}, "rolling_resistance": 0.1, "restitution": 0.5, "velocity": [1, 0, 0]}},
                  {{"name": "right", "kind": "granular", "blocks": [{{"min": [0.02, 0, 0], "max": [0.03, 0.01, 0.01]}}],
                   "radius": 0.005, "friction": {0}, "rolling_resistance": 0.1, "restitution": 0.5, "velocity": [-1, 0, 0]}}],
      "probes": [{{"name": "p", "type": "momentum", "object": "*"}},
                 {{"name": "L", "type": "momentum", "object": "*", "quantity": "angular"}},
                 {{"name": "E", "type": "energy", "object": "*", "quantity": "kinetic"}}]}})",
      mu, substeps, solver));
  const std::vector<double> before = w.probe_values();
  for (int s = 0; s < 60; ++s) w.step();
  const std::vector<double> after = w.probe_values();
  const Vec3 L0(before[3], before[4], before[5]), L(after[3], after[4], after[5]);
  return {Vec3(after[0], after[1], after[2]).norm(), (L - L0).norm() / L0.norm(), before[6], after[6]};
}

TEST(GrainRolling, GrainsMeetingOffCentreKeepMomentumAndAngularMomentum) {
  const Real mass = 2600 * 4 * kPi / 3 * 0.005 * 0.005 * 0.005;
  const Meeting frictionless = off_centre_meeting(0, 4), rough = off_centre_meeting(0.5, 4),
                rough_fine = off_centre_meeting(0.5, 16);
  std::printf("off-centre meeting: |p| %.1e kg m/s; |dL|/|L| %.3f %% without friction, %.3f %% with (h = 0.25 ms), "
              "%.3f %% with h = 62.5 us; E %.4e J -> %.4e J without friction, %.4e J with\n",
              rough.momentum, 100 * frictionless.angular_change, 100 * rough.angular_change,
              100 * rough_fine.angular_change, rough.energy_before, frictionless.energy_after, rough.energy_after);
  EXPECT_LT(rough.momentum, 1e-12 * mass);
  EXPECT_LT(rough.angular_change, 0.02);
  EXPECT_LT(rough_fine.angular_change, rough.angular_change / 3);  // first order in h
  EXPECT_LT(rough.energy_after, frictionless.energy_after);         // friction took energy into spin and heat
  EXPECT_LT(frictionless.energy_after, rough.energy_before);
}

// Under nmd both are kept to rounding: the impulses of the solve act at the contact point of the
// step's start, where they exert no net torque, and x+ = x + h v+ keeps each grain's orbital
// angular momentum x x m v+ (measured: 4e-15 of L).
TEST(GrainRolling, UnderNmdGrainsMeetingOffCentreKeepMomentumAndAngularMomentumToRounding) {
  const Real mass = 2600 * 4 * kPi / 3 * 0.005 * 0.005 * 0.005;
  const Meeting frictionless = off_centre_meeting(0, 1, "nmd"), rough = off_centre_meeting(0.5, 1, "nmd");
  std::printf("nmd, off-centre meeting: |p| %.1e kg m/s; |dL|/|L| %.1e without friction, %.1e with; E %.4e J -> "
              "%.4e J without friction, %.4e J with\n",
              rough.momentum, frictionless.angular_change, rough.angular_change, rough.energy_before,
              frictionless.energy_after, rough.energy_after);
  EXPECT_LT(rough.momentum, 1e-12 * mass);
  EXPECT_LT(frictionless.angular_change, 1e-12);
  EXPECT_LT(rough.angular_change, 1e-12);
  EXPECT_LT(rough.energy_after, frictionless.energy_after);
  EXPECT_LT(frictionless.energy_after, rough.energy_before);
}

// A grain set spinning at omega_0 about z (through the state array) on the ground: it slides,
// friction turns the spin into rolling, and it ends rolling at v = 2/7 omega_0 r, since friction
// acts at the contact point and keeps the angular momentum about it, (2/5) m r^2 omega_0 =
// (7/5) m r^2 omega (no rolling resistance). Sliding ends within 0.1 s; the friction then holds
// the rolling exactly: 1e-9 of the speed under xpbd, where the spin, solved with the slip in the
// same closed form, equals -v / r to 1e-6 rad/s (2e-7 of it); under nmd the converged solve of
// the one contact keeps both to rounding (measured: 1e-16 of the speed).
TEST(GrainRolling, ASpinningGrainSetOnTheGroundRollsAwayAtTwoSeventhsOfItsSpin) {
  for (const char* solver : {kXpbd, kNmd}) {
    World w = World::from_json(fmt::format(
        R"({{"name": "spin", "settings": {{{}, "duration": 1}},
        "objects": [{{"name": "ground", "kind": "collider", "shape": {{"type": "plane"}}}},
                    {{"name": "grain", "kind": "granular", "blocks": [{{"min": [0, 0, 0], "max": [0.01, 0.01, 0.01]}}],
                     "radius": 0.005, "friction": 0.5, "rolling_resistance": 0}}],
        "probes": [{{"name": "v", "type": "point", "object": "grain", "vertex": 0, "quantity": "velocity"}}]}})",
        solver));
    const Real omega0 = 20, r = 0.005;
    StateArray spin = w.array("particle.angular_velocity");
    ASSERT_EQ(spin.count, 1);
    spin.values[2] = -omega0;  // about -z: the bottom moves back, so the grain rolls towards +x
    while (w.time() < 0.5 - 1e-9) w.step();
    const Real v = w.probe_values()[0], expected = 2.0 / 7 * omega0 * r;
    const StateArray turn = w.array("particle.angular_velocity");
    std::printf("%s: a grain spun at %.0f rad/s set on the ground rolls at %.9f m/s (2/7 omega r = %.9f), spin %.6f rad/s\n",
                solver == kNmd ? "nmd" : "xpbd", omega0, v, expected, turn.values[2]);
    EXPECT_NEAR(v, expected, 1e-9 * expected + 1e-12) << solver;
    EXPECT_NEAR(turn.values[2], -v / r, 1e-6) << solver;
  }
}

// Under nmd a grain also turns against a rigid body. A grain spun at omega_0 about z is set on
// the middle of a free board of mass M that lies on a frictionless ground: friction at the
// contact point pushes the grain forward by an impulse P and the board back by -P until the
// grain rolls on the board, v + r omega = V, with m v = P, M V = -P and I (omega - omega_0) = r P
// (I = 2/5 m r^2), so P = -r omega_0 / (7 / (2 m) + 1 / M). The frictionless ground takes no
// horizontal impulse: the two momenta cancel to rounding (measured 2e-19 kg m/s). The grain is set
// touching the board: its lever is its distance to the board's surface, so a gap closed in one
// step would make the friction of that step act further out. The speeds match P to 1e-6 (measured
// 5e-8: the grain sinks into the board by the contact compliance).
TEST(GrainRolling, UnderNmdASpinningGrainSetOnAFreeBoardRollsAndPushesTheBoardBack) {
  const Real r = 0.005, m = 2600 * 4 * kPi / 3 * r * r * r, omega0 = 20;
  const Real board_density = 85, M = board_density * 0.04 * 0.01 * 0.04;
  World w = World::from_json(fmt::format(
      R"({{"name": "board", "settings": {{"solver": "nmd", "dt": 0.002, "duration": 1}},
      "objects": [{{"name": "ground", "kind": "collider", "shape": {{"type": "plane"}}, "friction": 0}},
                  {{"name": "board", "kind": "rigid_body", "density": {}, "friction": 0,
                    "shape": {{"type": "box", "size": [0.04, 0.01, 0.04]}}, "position": [0, 0.005, 0]}},
                  {{"name": "grain", "kind": "granular", "blocks": [{{"min": [-0.005, 0.0101, -0.005], "max": [0.005, 0.0201, 0.005]}}],
                    "radius": {}, "friction": 1.0, "rolling_resistance": 0}}],
      "probes": [{{"name": "v", "type": "point", "object": "grain", "vertex": 0, "quantity": "velocity"}},
                 {{"name": "board", "type": "momentum", "object": "board"}},
                 {{"name": "grain", "type": "momentum", "object": "grain"}}]}})",
      board_density, r));
  StateArray position = w.array("particle.position");
  ASSERT_EQ(position.count, 1);
  position.values[0] = position.values[2] = 0;  // on the board's middle, without the lattice's jitter,
  position.values[1] = 0.01 + r;                // touching its top
  StateArray spin = w.array("particle.angular_velocity");
  spin.values[2] = -omega0;  // rolls towards +x
  while (w.time() < 0.3 - 1e-9) w.step();
  const std::vector<double> p = w.probe_values();
  const Real P = r * omega0 / (3.5 / m + 1 / M);
  std::printf("nmd: a grain spun at %.0f rad/s on a free board rolls at %.9f m/s (P/m = %.9f), the board at %.9f m/s "
              "(-P/M = %.9f); momenta sum to %.1e kg m/s\n",
              omega0, p[0], P / m, p[3] / M, -P / M, p[3] + p[6]);
  EXPECT_NEAR(p[0], P / m, 1e-6 * P / m);
  EXPECT_NEAR(p[3] / M, -P / M, 1e-6 * P / M);
  EXPECT_LT(std::abs(p[3] + p[6]), 1e-12 * P);
}

// Under nmd a spinning grain that strikes a free cube off-centre (no gravity, mu = 0.5, e = 0.5)
// exchanges momentum and angular momentum with it: the pair's impulses act at one point, the
// cube's surface point (the grain's lever is its distance to it), so the total momentum and
// angular momentum (the grain's orbit and spin, the cube's) are kept to rounding; measured 1e-16
// and 1e-15. The cube's inertia is isotropic, so its explicit gyroscopic term is zero.
TEST(GrainRolling, UnderNmdASpinningGrainStrikingAFreeCubeKeepsTheTotalAngularMomentum) {
  World w = World::from_json(
      R"({"name": "strike", "settings": {"solver": "nmd", "dt": 0.001, "duration": 0.1, "gravity": [0, 0, 0]},
      "objects": [{"name": "cube", "kind": "rigid_body", "density": 100, "friction": 0.5, "restitution": 0.5,
                   "shape": {"type": "box", "size": [0.04, 0.04, 0.04]}, "position": [0, 0, 0]},
                  {"name": "grain", "kind": "granular", "blocks": [{"min": [-0.06, 0.005, -0.005], "max": [-0.05, 0.015, 0.005]}],
                   "radius": 0.005, "friction": 0.5, "restitution": 0.5, "rolling_resistance": 0.2, "velocity": [1, 0, 0]}],
      "probes": [{"name": "p", "type": "momentum", "object": "*"},
                 {"name": "L", "type": "momentum", "object": "*", "quantity": "angular"},
                 {"name": "cube", "type": "momentum", "object": "cube", "quantity": "angular"}]})");
  StateArray spin = w.array("particle.angular_velocity");
  ASSERT_EQ(spin.count, 1);
  spin.values[1] = 40;  // about y: friction on the cube's face pushes it along z
  spin.values[2] = -30;
  const std::vector<double> before = w.probe_values();
  for (int s = 0; s < 60; ++s) w.step();
  const std::vector<double> after = w.probe_values();
  const Vec3 p0(before[0], before[1], before[2]), p(after[0], after[1], after[2]);
  const Vec3 L0(before[3], before[4], before[5]), L(after[3], after[4], after[5]), cube(after[6], after[7], after[8]);
  std::printf("nmd: a spinning grain strikes a free cube: momentum changes by %.1e of its size, angular momentum by "
              "%.1e; the cube took %.3e kg m^2/s of it\n",
              (p - p0).norm() / p0.norm(), (L - L0).norm() / L0.norm(), cube.norm());
  EXPECT_GT(cube.norm(), 0.1 * L0.norm());  // the strike turned the cube
  EXPECT_LT((p - p0).norm(), 1e-12 * p0.norm());
  EXPECT_LT((L - L0).norm(), 1e-12 * L0.norm());
}

}  // namespace
}  // namespace moreau
