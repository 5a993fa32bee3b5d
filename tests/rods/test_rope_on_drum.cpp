// A rope wound on a turning drum lifts a box (scenes/cable_drum.json): the rope's contacts with the
// drum and with its own turns are solved with its joints in the direct solve (rigid/tree_contacts.hpp).
// Before, Gauss-Seidel pushed each 1.2 g segment out of the drum after the direct solve made the rope
// inextensible; the two undid each other, the rope stretched 0.6-2.4 % in 0.05 s and was thrown off.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "moreau/world.hpp"

namespace moreau {
namespace {

// The rope's length from its anchor on the drum to the hook, for a flexible rope wound at radius
// rho = R + r (its centreline) with pitch p and hanging straight from the tangent point:
//   L = rho_h (theta_anchor - theta_tangent) + sqrt(d^2 - rho^2),  rho_h = sqrt(rho^2 + (p / 2 pi)^2)
// with d the hook's distance from the drum's axis and theta_tangent = atan2(y, x) + acos(rho / d)
// (the rope leaves the drum going clockwise). theta_anchor = 3 pi + omega t: the anchor turns with
// the drum from 1.5 turns round.
double rope_length(double x, double y, double t) {
  const double rho = 0.104, omega = 1, pitch = 0.012;
  const double rho_h = std::sqrt(rho * rho + std::pow(pitch / (2 * M_PI), 2));
  const double d = std::hypot(x, y);
  return rho_h * (3 * M_PI + omega * t - (std::atan2(y, x) + std::acos(rho / d))) + std::sqrt(d * d - rho * rho);
}

// The drum (R = 0.1 m, 1 rad/s) winds the rope (r = 4 mm, E = 2 GPa, 87 segments) that holds the
// 5 kg box. Checked over 1 s (60 steps):
// - the rope's length from the anchor to the hook grows by its stretch under the box's weight,
//   m g L / (E A) = 0.87 mm. At the start the weight comes on at once (which doubles the stretch
//   at its peak) and the drum jerks the box to 0.104 m/s (v / omega_n = 0.98 mm more, the box
//   bouncing on the rope at omega_n = sqrt(E A / (m L)) = 106 rad/s): the peak stays below their
//   sum. At 1 s the hanging part is stretched by the weight, and the wound part by no more (friction
//   holds the turns, whose tension falls towards the anchor as the capstan's): the stretch lies
//   between m g L_hanging / (E A) and m g L / (E A), within 10 % (what is left of the bounce).
//   A taut rope is never shorter than at rest: the length may dip below its start by no more than
//   a tenth of the stretch (the same bounce);
// - the box rises at (R + r) omega = 0.104 m/s once the start's transient has passed (measured
//   from 0.5 s to 1 s): within 1 % (what the bounce's amplitude v / omega_n = 1 mm leaves after
//   0.5 s, and the wound polygon's excess length, dtheta^2 / 24 = 0.16 %).
TEST(RopeOnDrum, TheDrumLiftsTheBoxWithoutStretchingTheRope) {
  World w = World::load(std::string(MOREAU_SOURCE_DIR) + "/scenes/cable_drum.json");
  const std::vector<std::string> names = w.probe_names();
  auto column = [&](const std::string& name) {
    return static_cast<size_t>(std::find(names.begin(), names.end(), name) - names.begin());
  };
  const size_t box_y = column("box.y"), hook_x = column("hook.x"), hook_y = column("hook.y");
  const double drum_y = 1.0, g = 9.81, mass = 5, E = 2e9, area = M_PI * 0.004 * 0.004;
  std::vector<double> v = w.probe_values();
  const double length0 = rope_length(v[hook_x], v[hook_y] - drum_y, 0);
  const double stretch = mass * g * length0 / (E * area);
  const double bounce = 0.104 / std::sqrt(E * area / (mass * length0));
  double largest = 0, smallest = 0, last = 0, hanging = 0, box_half = 0;
  for (int step = 1; step <= 60; ++step) {
    w.step();
    v = w.probe_values();
    const double change = rope_length(v[hook_x], v[hook_y] - drum_y, w.time()) - length0;
    largest = std::max(largest, change);
    smallest = std::min(smallest, change);
    last = change;
    const double d = std::hypot(v[hook_x], v[hook_y] - drum_y);
    hanging = std::sqrt(d * d - 0.104 * 0.104);
    if (step == 30) box_half = v[box_y];
  }
  const double speed = (v[box_y] - box_half) / 0.5, expected = 0.104;
  const double hanging_stretch = mass * g * hanging / (E * area);
  std::printf("rope on a drum: the rope's length from anchor to hook changed by %.3f to %.3f mm (m g L / (E A) = %.3f mm, "
              "the start's bounce %.3f mm), %.3f mm at 1 s (between %.3f and %.3f mm); the box rose at %.5f m/s from 0.5 to 1 s "
              "((R + r) omega = %.3f m/s, %+.2f %%)\n",
              smallest * 1e3, largest * 1e3, stretch * 1e3, bounce * 1e3, last * 1e3, hanging_stretch * 1e3, stretch * 1e3,
              speed, expected, 100 * (speed / expected - 1));
  EXPECT_LT(largest, 2 * stretch + bounce);
  EXPECT_GT(smallest, -0.1 * stretch);
  EXPECT_GT(last, 0.9 * hanging_stretch);
  EXPECT_LT(last, 1.1 * stretch);
  EXPECT_NEAR(speed, expected, 0.01 * expected);
}

}  // namespace
}  // namespace moreau
