// The stability goals, on the reference scenes of bench/scenes (generate_rigid_scenes.py),
// where established engines fail: a light chain holding a heavy weight, and a 2D box pyramid.
#include <gtest/gtest.h>
#include <fmt/format.h>

#include <filesystem>

#include "test_helpers.hpp"

namespace moreau {
namespace {

using test::run_steps;

Scene bench_scene(const std::string& file, const std::vector<std::string>& overrides = {}) {
  return load_scene((std::filesystem::path(MOREAU_SOURCE_DIR) / "bench" / "scenes" / file).string(), overrides);
}

// The chain's stretch: the sum of every joint's gap over the 10 m of links.
Real chain_stretch(const Scene& s) {
  Real gaps = 0;
  for (Index j = 0; j < static_cast<Index>(s.model.joints.size()); ++j) gaps += joint_error(s.model.joints[j], s.state).position;
  return gaps / 10.0;
}

// Runs `steps` steps; returns the largest stretch and the weight's lowest height on the way.
std::pair<Real, Real> largest_stretch(Scene& s, long steps) {
  const Index weight = s.model.objects[s.model.find_object("weight")].body;
  Real worst = 0, lowest = s.state.rigid.position[weight].y();
  for (long k = 0; k < steps; ++k) {
    run_steps(s, 1);
    worst = std::max(worst, chain_stretch(s));
    lowest = std::min(lowest, s.state.rigid.position[weight].y());
  }
  return {worst, lowest};
}

TEST(RigidStability, HundredLinkChainHoldingAThousandTimesItsLinkMassDoesNotStretch) {
  // 100 links of 0.1 kg on ball joints hold 100 kg (Bullet: +1068 %, MuJoCo: +1029 %; goal 1 %).
  // The direct tree solver re-linearises until every joint row is below 1e-9 m, so 101 joints
  // leave at most ~1e-7 m, 1e-8 of the length; 1e-6 bounds that with margin, where Gauss-Seidel
  // at the same 20 substeps stretches the hanging chain by 14 % and tears the released one.
  Scene hanging = bench_scene("chain_100_hanging.json");
  ASSERT_EQ(hanging.model.joint_forest.nodes.size(), 101u + 101u);  // every joint and body in one tree
  const Real hanging_stretch = largest_stretch(hanging, 120).first;
  // Released from horizontal: the weight swings through the bottom at ~14 m/s around 1.6 s, when
  // the links carry ~3 kN.
  Scene released = bench_scene("chain_100_released.json");
  const auto [released_stretch, lowest] = largest_stretch(released, 180);
  fmt::print("chain stretch: hanging {:.3g}, released {:.3g} (relative)\n", hanging_stretch, released_stretch);
  EXPECT_LT(hanging_stretch, 1e-6);
  EXPECT_LT(released_stretch, 1e-6);
  // It did swing down: the weight passed within 1 % of the chain's length of the lowest point it
  // can reach (0.1 m below the chain's 10 m), i.e. the links did not give way.
  EXPECT_LT(lowest, 10 - 10.1 + 0.1);
  EXPECT_GT(lowest, 10 - 10.1 * 1.01);
}

TEST(RigidStability, PyramidOf210BoxesStandsTenSeconds) {
  // A 2D pyramid of 210 unit cubes (base 20), friction 0.5, 10 s at 60 Hz and 8 substeps (Bullet:
  // 7.4 cm drift, MuJoCo loses a box; goal 1 cm). It settles by 0.5 mm under its weight in the
  // first second and then holds: static friction carries its leftover slip (rigid_contacts.hpp).
  Scene s = bench_scene("pyramid_210.json");
  Real drift = 0;
  for (int second = 0; second < 10; ++second) {
    run_steps(s, 60);
    for (Index b = 0; b < s.model.rigid.count(); ++b)
      if (s.model.rigid.is_dynamic(b))
        drift = std::max(drift, (s.state.rigid.position[b] - s.model.rigid.initial_position[b]).norm());
  }
  fmt::print("pyramid: largest drift {:.3g} m in 10 s\n", drift);
  EXPECT_LT(drift, 0.01);
}

}  // namespace
}  // namespace moreau
