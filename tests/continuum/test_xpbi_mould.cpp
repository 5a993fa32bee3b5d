// The mould showcase (scenes/plasticine_mould.json): a rigid piston pushes a block of von Mises
// plasticine through a square hole. Whatever the flow, the plasticine left in the chamber must
// fill the chamber: its particles' rest volumes times their det F add up to the space below the
// piston.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <string>

#include "moreau/scene/scene.hpp"

namespace moreau {
namespace {

TEST(XpbiMould, ThePlasticineLeftInTheChamberFillsIt) {
  Scene scene = load_scene(std::string(MOREAU_SOURCE_DIR) + "/scenes/plasticine_mould.json");
  StageTimer timer;
  const Real dt = scene.model.settings.dt, press_time = 0.6, speed = 0.05;
  for (long k = 0; k < std::lround(press_time / dt); ++k) scene.formulation->step(scene.model, scene.state, timer, 1);
  // The chamber: 6 x 6 cm, from its floor y = 0 to the piston's face, 6 cm less the 3 cm it went.
  const Real chamber = 0.06 * 0.06 * (0.06 - speed * press_time);
  const ContinuumModel& c = scene.model.continuum;
  Real held = 0, rest = 0, below = 0;
  for (Index i = 0; i < c.size(); ++i) {
    const Index p = c.particle[i];
    if (scene.state.position[p].y() > 0) {
      held += c.rest_volume[i] * scene.state.continuum.deformation[i].determinant();
      rest += c.rest_volume[i];
    } else if (scene.state.position[p].y() < -0.01) {
      below += scene.model.particle_mass[p];
    }
  }
  const Real density = 1500, displaced = density * 0.06 * 0.06 * speed * press_time;
  fmt::print("chamber {:.1f} cm^3: its particles' V0 det F {:.1f} cm^3 ({:+.1f} %), V0 {:.1f} cm^3; "
             "extruded {:.4f} kg, the piston displaced {:.4f} kg\n",
             1e6 * chamber, 1e6 * held, 100 * (held / chamber - 1), 1e6 * rest, below, displaced);
  // det F follows the particles' packing once they pack 10 % closer than it says
  // (continuum/packing_volume.hpp); without that the chamber's particles claimed 21 % more volume
  // than the chamber has.
  EXPECT_NEAR(held / chamber, 1, 0.1);
  // The displaced 0.162 kg is what came out plus what fills the hole (4 cm^3, 0.006 kg) plus what
  // the chamber's compression keeps: its mean det F is 0.96 under the extrusion pressure and its
  // particles may pack 10 % closer than that, at most 14 % of its 0.18 kg, 0.025 kg. So at least
  // 0.131 kg, 0.81 of the displaced mass, comes out, and never more than all of it.
  EXPECT_GT(below, 0.8 * displaced);
  EXPECT_LT(below, displaced);
}

}  // namespace
}  // namespace moreau
