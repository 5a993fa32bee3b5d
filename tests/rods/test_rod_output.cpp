// A rod's frame file: the centreline polyline of a helix at rest, its curvature against the
// helix's R / (R^2 + c^2), and the material frame per segment.
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <string>

#include "moreau/math/types.hpp"
#include "moreau/world.hpp"
#include "test_helpers.hpp"
#include "vtk_read.hpp"

namespace moreau {
namespace {

// A weightless helix of radius R = 0.1 m and pitch 0.05 m (c = pitch / 2 pi), two turns in 64
// segments, free at both ends: at rest its junctions' curvature is that of the helix,
// R / (R^2 + c^2) = 9.937 1/m, to the chord's O((turn per segment)^2) (0.4 % at 1/32 of a turn),
// its twist and stretch are 0, and every segment's tangent is the chord's direction.
TEST(RodOutput, HelixFrameFileCarriesTheCentrelineAndItsCurvature) {
  const std::string out = test::temp_dir("rod-output");
  World w = World::from_json(R"({"name": "helix", "settings": {"dt": 0.01, "duration": 0.01, "gravity": [0, 0, 0]},
      "objects": [{"name": "spring", "kind": "rod", "helix": {"center": [0, 0, 0], "axis": [0, 1, 0], "radius": 0.1,
                   "pitch": 0.05, "turns": 2}, "segments": 64, "radius": 0.005, "youngs_modulus": 1e9, "density": 1000}]})");
  RunOptions options;
  options.out_dir = out;
  w.run(options);
  const std::string file = out + "/frames/spring_000000.vtp";
  std::ifstream in(file);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("NumberOfPoints=\"65\""), std::string::npos);
  EXPECT_NE(text.find("NumberOfLines=\"64\""), std::string::npos);

  const std::vector<double> points = test::read_appended_float64(file, "displacement");
  const std::vector<double> curvature = test::read_appended_float64(file, "curvature");
  const std::vector<double> twist = test::read_appended_float64(file, "twist");
  const std::vector<double> tangent = test::read_appended_float64(file, "tangent");
  ASSERT_EQ(curvature.size(), 65u);
  ASSERT_EQ(tangent.size(), 3u * 64);
  const Real R = 0.1, c = 0.05 / (2 * kPi), helix = R / (R * R + c * c);
  for (int k = 1; k < 64; ++k) {
    EXPECT_NEAR(curvature[k] / helix, 1, 0.005) << k;
    EXPECT_NEAR(twist[k], 0, 1e-9) << k;
  }
  EXPECT_EQ(curvature[0], 0);
  EXPECT_EQ(curvature[64], 0);
  for (double d : points) EXPECT_NEAR(d, 0, 1e-9);  // the first frame is the rest shape
  // The helix's tangent rises at c / sqrt(R^2 + c^2) of its length.
  for (int s = 0; s < 64; ++s) EXPECT_NEAR(tangent[3 * s + 1], c / std::sqrt(R * R + c * c), 1e-3) << s;
  std::printf("rod output, helix R = 0.1 m, 64 segments: curvature %.5f 1/m at the first junction, helix %.5f 1/m\n",
              curvature[1], helix);
}

}  // namespace
}  // namespace moreau
