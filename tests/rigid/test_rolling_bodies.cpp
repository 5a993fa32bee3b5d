// Round rigid bodies rolling without slipping, against the rigid-body equations of motion. A body
// of mass m, radius R and moment of inertia I about its axis rolls down a slope of angle theta at
//   a = g sin(theta) / (1 + I / (m R^2))
// (no slip: the contact point is at rest, so friction does no work), as long as the friction it
// needs, tan(theta) k / (1 + k) with k = I / (m R^2), stays below mu. On level ground it keeps its
// speed and its centre stays at the height R.
#include <gtest/gtest.h>
#include <fmt/format.h>

#include <cmath>

#include "moreau/collision/shape.hpp"
#include "test_helpers.hpp"

namespace moreau {
namespace {

using test::run_steps;
using test::scene_from_json;

constexpr Real kGravity = 9.81;
constexpr Real kRadius = 0.1;

Index body_of(const Scene& s, const std::string& name) { return s.model.objects[s.model.find_object(name)].body; }

// The shape's JSON with its axis turned from y to z (across a slope that descends towards +x).
struct RoundBody {
  const char* name;
  std::string shape_json;
  Shape shape;
};

std::vector<RoundBody> round_bodies() {
  return {{"sphere", fmt::format(R"({{"type": "sphere", "radius": {}}})", kRadius), make_sphere(kRadius)},
          {"cylinder", fmt::format(R"({{"type": "cylinder", "radius": {}, "half_height": 0.15}})", kRadius),
           make_cylinder(kRadius, 0.15)},
          {"capsule", fmt::format(R"({{"type": "capsule", "radius": {}, "half_height": 0.15}})", kRadius),
           make_capsule(kRadius, 0.15)}};
}

// k = I / (m R^2) about the body's own y axis (its axis of symmetry).
Real inertia_ratio(const Shape& shape) {
  const MassProperties p = mass_properties(shape);
  return p.inertia(1, 1) / (p.volume * kRadius * kRadius);
}

// A 30 degree slope (a box collider) with the body resting on it, axis across the slope.
std::string slope_scene(const RoundBody& body, Real mu) {
  const Real theta = kPi / 6, lift = 0.5 + kRadius;
  return fmt::format(R"({{"name": "roll", "settings": {{"dt": {}, "substeps": 20}},
    "objects": [
      {{"name": "slope", "kind": "collider", "friction": {},
        "shape": {{"type": "box", "center": [0, 0, 0], "half_extents": [10, 0.5, 2], "rotation_deg": [0, 0, -30]}}}},
      {{"name": "body", "kind": "rigid_body", "shape": {}, "rotation_deg": [90, 0, 0],
        "position": [{}, {}, 0], "density": 1000, "friction": {}}}]}})",
                     1.0 / 60, mu, body.shape_json, lift * std::sin(theta), lift * std::cos(theta), mu);
}

TEST(RollingBodies, SphereCylinderAndCapsuleRollDownASlopeAtTheRollingAcceleration) {
  // 2 s from rest, mu = 0.8 (rolling needs at most 0.19 here). The distance is a t^2 / 2 with
  // a = g sin 30 / (1 + k): k = 2/5 for the sphere, 1/2 for the cylinder, in between for the
  // capsule. We measure +0.033 % for all three (the step's lag of one substep in the start); held
  // to 0.2 %. Turning the bodies with the first-order quaternion update lost spin at every
  // substep, (w h)^2 / 8, and all three came 2.7 % short; a cylinder whose slab contact came from
  // MPR alone was thrown 4 m along the slab near its end.
  for (const RoundBody& body : round_bodies()) {
    Scene s = scene_from_json(slope_scene(body, 0.8));
    const Index b = body_of(s, "body");
    const Vec3 start = s.state.rigid.position[b];
    run_steps(s, 120);
    const Real k = inertia_ratio(body.shape);
    const Real expected = 0.5 * kGravity * std::sin(kPi / 6) / (1 + k) * 4;
    const Real distance = (s.state.rigid.position[b] - start).norm();
    // Rolling: the contact point at rest, v = omega R. We measure 1e-9 m/s; held to 0.1 % of v,
    // far below the 3.4 m/s of slip a cylinder showed when its contact was taken from MPR alone.
    const Real speed = s.state.rigid.velocity[b].norm(), spin = s.state.rigid.angular_velocity[b].norm();
    std::printf("%s rolls down 30 degrees: %.5f m in 2 s (exact %.5f m, %+.3f %%), v - omega R = %.2e m/s\n",
                body.name, distance, expected, 100 * (distance / expected - 1), speed - spin * kRadius);
    EXPECT_NEAR(distance, expected, 0.002 * expected) << body.name;
    EXPECT_NEAR(speed, spin * kRadius, 1e-3 * speed) << body.name;
  }
}

TEST(RollingBodies, CylinderRollsOnLevelGroundAtItsRadiusAndKeepsItsSpeed) {
  // A wheel rolling at 1 m/s turns 0.17 rad per step. Its centre stays at R (the contact is taken
  // from the axis, so it stays under the wheel as the wheel turns): we measure 0.13 micrometres,
  // what the position solve leaves of a substep's fall, and hold it to 1 micrometre. Its speed
  // stays within 1e-6 m/s over 2 s (the wheel neither slips nor loses spin; we measure
  // round-off). Both bounds are over a thousand times below the defect they guard: anchored on
  // the rim, the contact was carried up with the material between detections, the centre sank
  // 1.4 mm and the wheel sped up 2.7 %.
  const std::string json = fmt::format(R"({{"name": "wheel", "settings": {{"dt": {}, "substeps": 20}},
    "objects": [
      {{"name": "ground", "kind": "collider", "shape": {{"type": "plane"}}, "friction": 0.8}},
      {{"name": "wheel", "kind": "rigid_body", "shape": {{"type": "cylinder", "radius": {}, "half_height": 0.05}},
        "position": [0, {}, 0], "rotation_deg": [90, 0, 0], "velocity": [1, 0, 0], "angular_velocity": [0, 0, {}],
        "density": 1000, "friction": 0.8}}]}})",
                                       1.0 / 60, kRadius, kRadius, -1 / kRadius);
  Scene s = scene_from_json(json);
  const Index b = body_of(s, "wheel");
  Real lowest = kRadius, highest = kRadius;
  for (int step = 0; step < 120; ++step) {
    run_steps(s, 1);
    lowest = std::min(lowest, s.state.rigid.position[b].y());
    highest = std::max(highest, s.state.rigid.position[b].y());
  }
  const Real speed = s.state.rigid.velocity[b].x();
  std::printf("wheel on level ground: centre height in [%.8f, %.8f] m (R = %.2f m), speed %.9f m/s after 2 s\n",
              lowest, highest, kRadius, speed);
  EXPECT_NEAR(lowest, kRadius, 1e-6);
  EXPECT_NEAR(highest, kRadius, 1e-6);
  EXPECT_NEAR(speed, 1.0, 1e-6);
}

}  // namespace
}  // namespace moreau
