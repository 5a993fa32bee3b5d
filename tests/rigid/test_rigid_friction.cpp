// Coulomb friction of rigid contacts against the analytic sliding laws, for every kind of slope
// (plane collider, box collider, fixed rigid body) tilted either way: the answer must not depend on
// the orientation of the slope or on the order of a manifold's rows.
#include <gtest/gtest.h>
#include <fmt/format.h>

#include <cmath>

#include "test_helpers.hpp"

namespace moreau {
namespace {

using test::run_steps;
using test::scene_from_json;

constexpr Real kTheta = kPi / 6;  // 30 degree slope
constexpr Real kHalf = 0.1;       // the sliding box: a 0.2 m cube of density 1000 (8 kg)

enum class Slope { plane_collider, box_collider, fixed_body };

// A slope through the origin whose outward normal is (-side sin 30, cos 30, 0) (side = +1 or -1:
// the two mirror images) and the box resting flat on it, yawed by `yaw_deg` about the normal.
std::string slope_scene(Slope slope, int side, Real mu, Real yaw_deg) {
  const Vec3 n(-side * std::sin(kTheta), std::cos(kTheta), 0);
  const Real tilt = side * 30.0;
  std::string ground;
  Real surface = 0;  // distance from the origin to the slope's surface along n
  switch (slope) {
    case Slope::plane_collider:
      ground = fmt::format(R"({{"name": "slope", "kind": "collider", "friction": {},
        "shape": {{"type": "plane", "normal": [{}, {}, 0], "offset": 0}}}})",
                           mu, n.x(), n.y());
      break;
    case Slope::box_collider:
      ground = fmt::format(R"({{"name": "slope", "kind": "collider", "friction": {},
        "shape": {{"type": "box", "center": [0, 0, 0], "half_extents": [10, 0.5, 3], "rotation_deg": [0, 0, {}]}}}})",
                           mu, tilt);
      surface = 0.5;
      break;
    case Slope::fixed_body:
      ground = fmt::format(R"({{"name": "slope", "kind": "rigid_body", "fixed": true, "friction": {},
        "shape": {{"type": "box", "half_extents": [10, 0.5, 3]}}, "position": [0, 0, 0],
        "rotation_deg": [0, 0, {}]}})",
                           mu, tilt);
      surface = 0.5;
      break;
  }
  const Vec3 center = (surface + kHalf) * n;
  return fmt::format(R"({{"name": "slope", "settings": {{"dt": {}, "substeps": 20}},
    "objects": [{},
      {{"name": "box", "kind": "rigid_body", "shape": {{"type": "box", "half_extents": [{}, {}, {}]}},
        "position": [{}, {}, 0], "rotation_deg": [0, {}, {}], "density": 1000, "friction": {}}}]}})",
                     1.0 / 60, ground, kHalf, kHalf, kHalf, center.x(), center.y(), yaw_deg, tilt, mu);
}

const char* slope_name(Slope s) {
  switch (s) {
    case Slope::plane_collider: return "plane collider";
    case Slope::box_collider: return "box collider";
    case Slope::fixed_body: return "fixed rigid body";
  }
  return "";
}

TEST(RigidFriction, BoxSlidesTheCoulombDistanceOnEverySlopeEitherWay) {
  // mu_s = mu_k = 0.5 < tan 30: s = g (sin 30 - mu cos 30) t^2 / 2 = 1.3143 m after 2 s, straight
  // down the slope, for every slope kind and direction (each manifold's block is solved to
  // convergence). The speed after 2 s is exact (1.31431 against 1.31429 m/s); the distance is
  // +0.58 % (1.32192 m) because the velocity pass's dynamic friction reaches the positions one
  // substep late: mu g cos(theta) h t = 7.1 mm at h = 1/1200 s, first order in h. 1 % bounds it.
  const Real mu = 0.5, expected = 0.5 * 9.81 * (std::sin(kTheta) - mu * std::cos(kTheta)) * 4;
  Real first = 0;
  for (const Slope slope : {Slope::plane_collider, Slope::box_collider, Slope::fixed_body})
    for (const int side : {1, -1})
      for (const Real yaw : {0.0, 20.0}) {
        Scene s = scene_from_json(slope_scene(slope, side, mu, yaw));
        const Index b = s.model.objects[s.model.find_object("box")].body;
        const Vec3 start = s.state.rigid.position[b];
        run_steps(s, 120);
        const Vec3 moved = s.state.rigid.position[b] - start;
        const Vec3 downhill(-side * std::cos(kTheta), -std::sin(kTheta), 0);
        const std::string where = fmt::format("{}, side {}, yaw {}", slope_name(slope), side, yaw);
        std::printf("%s: slid %.5f m (exact %.5f), sideways %.2e m, |w| %.2e rad/s\n", where.c_str(), moved.norm(),
                    expected, (moved - moved.dot(downhill) * downhill).norm(),
                    s.state.rigid.angular_velocity[b].norm());
        EXPECT_NEAR(moved.dot(downhill), expected, 0.01 * expected) << where;
        // Straight down the slope and without spin. With three sweeps per block the box turned at
        // 2e-3 to 3e-2 rad/s and drifted 2e-5 to 7e-5 m sideways; converged, we measure at most
        // 3e-7 rad/s and 2e-9 m (what the blocks' 1e-9 tolerance leaves).
        EXPECT_LT((moved - moved.dot(downhill) * downhill).norm(), 2e-6) << where;
        EXPECT_LT(s.state.rigid.angular_velocity[b].norm(), 1e-6) << where;
        // The same distance for every slope and direction (measured: equal to 1e-5 m; it was 6 % apart).
        if (first == 0) first = moved.norm();
        EXPECT_NEAR(moved.norm(), first, 1e-4 * first) << where;
      }
}

TEST(RigidFriction, FastBoxSlidesFlatOnAPlane) {
  // A 0.2 m cube launched at 10 m/s along a plane with mu = 0.1 decelerates at mu g and stays
  // flat: x(t) = v0 t - mu g t^2 / 2 = 9.5095 m after 1 s. (Its contact margin, 2 dt |v| = 0.33 m,
  // is larger than the cube; only the approach along the normal can bring a corner to the plane.)
  const Real mu = 0.1, v0 = 10;
  Scene s = scene_from_json(fmt::format(R"({{"name": "fast", "settings": {{"dt": {}, "substeps": 20}},
    "objects": [{{"name": "ground", "kind": "collider", "friction": {}, "shape": {{"type": "plane"}}}},
      {{"name": "box", "kind": "rigid_body", "shape": {{"type": "box", "half_extents": [0.1, 0.1, 0.1]}},
        "position": [0, 0.1, 0], "velocity": [{}, 0, 0], "density": 1000, "friction": {}}}]}})",
                                        1.0 / 60, mu, v0, mu));
  const Index b = s.model.objects[s.model.find_object("box")].body;
  Real lowest_up = 1;
  for (int step = 0; step < 60; ++step) {
    run_steps(s, 1);
    lowest_up = std::min(lowest_up, (s.state.rigid.orientation[b] * Vec3::UnitY()).y());
  }
  const Real expected = v0 * 1 - 0.5 * mu * 9.81;
  std::printf("fast box: x = %.5f m (exact %.5f), lowest cos(tilt) %.9f, y = %.6f\n", s.state.rigid.position[b].x(),
              expected, lowest_up, s.state.rigid.position[b].y());
  EXPECT_GT(lowest_up, std::cos(1e-3));  // never tilts by more than a milliradian
  EXPECT_NEAR(s.state.rigid.position[b].y(), 0.1, 1e-3);
  EXPECT_NEAR(s.state.rigid.position[b].x(), expected, 0.01 * expected);
}

}  // namespace
}  // namespace moreau
