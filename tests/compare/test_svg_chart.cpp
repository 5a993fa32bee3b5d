// The comparison's plots: ticks at round values, lines broken where a value is missing.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "moreau/compare/svg_chart.hpp"

namespace moreau {
namespace {

TEST(SvgChart, TicksAreRoundStepsCoveringTheRange) {
  // About five ticks at 1, 2 or 5 times a power of ten, all inside the range.
  const std::vector<double> unit = round_ticks(0, 1);
  ASSERT_EQ(unit.size(), 6u);
  for (size_t i = 0; i < unit.size(); ++i) EXPECT_NEAR(unit[i], 0.2 * i, 1e-15);
  EXPECT_EQ(round_ticks(-3.7, 12.2), (std::vector<double>{0, 5, 10}));
  const std::vector<double> small = round_ticks(2.4525e-4, 2.4530e-4);
  ASSERT_GE(small.size(), 2u);
  EXPECT_GE(small.front(), 2.4525e-4);
  EXPECT_LE(small.back(), 2.4530e-4);
  EXPECT_NEAR(small[1] - small[0], 1e-8, 1e-20);
}

TEST(SvgChart, AMissingValueBreaksTheLineAndTextIsEscaped) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  LineChart chart{"a < b & c", "time (s)", "m", {{"xpbd", {0, 1, 2, 3, 4}, {0, 1, nan, 3, 4}}}};
  const std::string svg = svg_line_chart(chart);
  // The path starts again after the gap: two move-to commands.
  const size_t path = svg.find("<path d=\"");
  ASSERT_NE(path, std::string::npos);
  const std::string d = svg.substr(path, svg.find('"', path + 9) - path);
  EXPECT_EQ(std::count(d.begin(), d.end(), 'M'), 2) << d;
  EXPECT_NE(svg.find("a &lt; b &amp; c"), std::string::npos);
  EXPECT_EQ(svg.find("a < b"), std::string::npos);
}

}  // namespace
}  // namespace moreau
