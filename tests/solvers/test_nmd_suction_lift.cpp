// A suction cup sealed on a rigid body under "nmd": the cavity's row acts on the body as well,
// so the air sealed under the cup lifts the plate it sits on (scenes/suction_lift.json).
#include <gtest/gtest.h>

#include <cstdio>

#include "test_helpers.hpp"

namespace moreau {
namespace {

TEST(NmdSuction, CupLiftsAPlateAndTheDriveCarriesTheWeightOfAll) {
  // The handle is driven up at 5 cm/s; the cup seals on the 0.5 kg plate and lifts it off the
  // floor. Over 0.2-0.5 s everything rises at the drive's speed, so (momentum balance) the drive
  // carries the weight of handle, cup and plate; the plate hangs from the air alone, so the
  // suction over the sealed area, A dp, at least carries the plate's weight (the rim also presses
  // on the plate: A dp = m g + rim force). Tolerances: 2 % for the drive (what accelerations are
  // left in the cup; measured 5e-5), 2 % below m g for A dp (measured 0.5 % below at its least: the
  // plate still swings a little about its hanging state, and A dp with it), 3 % for the plate's speed (the cup
  // stretches 0.25 mm over the window as the suction rises: 1.7 % slower).
  Scene s = load_scene(std::string(MOREAU_SOURCE_DIR) + "/scenes/suction_lift.json");
  const Real h = s.model.settings.dt, g = 9.81;
  const Index slider = 0;
  const Index plate = s.model.objects[s.model.find_object("plate")].body;
  const Real plate_weight = g / s.model.rigid.body_inv_mass[plate];
  Real total_weight = 0;
  for (const ObjectInfo& o : s.model.objects) {
    if (o.kind == ObjectKind::rigid_body) total_weight += g / s.model.rigid.body_inv_mass[o.body];
    for (Index p = o.particle_begin; p < o.particle_end; ++p) total_weight += g * s.model.particle_mass[p];
  }
  test::run_steps(s, 200);
  const Real y_start = s.state.rigid.position[plate].y();
  Real drive = 0, suction = 0, least_suction = 1e300;
  int n = 0;
  bool sealed = true;
  for (int step = 200; step < 500; ++step) {
    test::run_steps(s, 1);
    drive += s.state.joint_lambda[slider][JointSlot::drive] / (h * h);
    const SuctionCupState& cup = s.state.suction[0];
    sealed &= cup.sealed;
    suction += cup.area * cup.pressure_difference;
    least_suction = std::min(least_suction, cup.area * cup.pressure_difference);
    ++n;
  }
  drive /= n;
  suction /= n;
  const Real speed = (s.state.rigid.position[plate].y() - y_start) / (300 * h);
  std::printf("lift 0.2-0.5 s: drive %.4f N (weight of all %.4f N), A dp mean %.4f N, least %.4f N (plate %.4f N), plate speed %.5f m/s (drive 0.05)\n",
              drive, total_weight, suction, least_suction, plate_weight, speed);
  EXPECT_TRUE(sealed);
  EXPECT_NEAR(drive, total_weight, 0.02 * total_weight);
  EXPECT_GT(least_suction, 0.98 * plate_weight);
  EXPECT_NEAR(speed, 0.05, 0.03 * 0.05);
}

}  // namespace
}  // namespace moreau
