#pragma once
// A line chart as a standalone SVG document: one time series per line on shared axes, with
// ticks at round values and a legend. What `moreau compare` draws for each probe column.
#include <string>
#include <vector>

namespace moreau {

struct ChartLine {
  std::string label;
  std::vector<double> x, y;  // equal lengths; non-finite points break the line
};

struct LineChart {
  std::string title, x_label, y_label;
  std::vector<ChartLine> lines;
};

/// Text with &, <, > and " escaped, for XML (SVG) and HTML.
std::string escape_xml(const std::string& text);

/// The chart as an SVG document (width x height pixels).
std::string svg_line_chart(const LineChart& chart, int width = 640, int height = 320);

/// Tick values at round steps (1, 2 or 5 times a power of ten) covering [low, high], about
/// `wanted` of them.
std::vector<double> round_ticks(double low, double high, int wanted = 5);

}  // namespace moreau
