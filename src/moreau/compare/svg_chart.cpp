#include "moreau/compare/svg_chart.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace moreau {

namespace {

// Colours that stay distinct for readers with the common colour-vision deficiencies (Okabe & Ito).
constexpr const char* kColours[] = {"#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9"};

struct AxisRange {
  double low = std::numeric_limits<double>::infinity(), high = -std::numeric_limits<double>::infinity();
  void add(double v) {
    if (!std::isfinite(v)) return;
    low = std::min(low, v);
    high = std::max(high, v);
  }
  // A range to draw: a constant series gets a band around its value, an empty one [0, 1].
  AxisRange padded() const {
    if (!(low <= high)) return {0, 1};
    if (high - low > 1e-12 * std::max(std::abs(low), std::abs(high))) return *this;
    const double half = low == 0 ? 1 : 0.05 * std::abs(low);
    return {low - half, high + half};
  }
};

}  // namespace

std::string escape_xml(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '&') out += "&amp;";
    else if (c == '<') out += "&lt;";
    else if (c == '>') out += "&gt;";
    else if (c == '"') out += "&quot;";
    else out += c;
  }
  return out;
}

std::vector<double> round_ticks(double low, double high, int wanted) {
  const double raw = (high - low) / std::max(wanted, 1);
  const double power = std::pow(10.0, std::floor(std::log10(raw)));
  double step = power;
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (m * power >= raw) {
      step = m * power;
      break;
    }
  std::vector<double> ticks;
  for (double t = std::ceil(low / step - 1e-9) * step; t <= high + 1e-9 * step; t += step)
    ticks.push_back(std::abs(t) < 1e-12 * step ? 0.0 : t);
  return ticks;
}

std::string svg_line_chart(const LineChart& chart, int width, int height) {
  const double left = 78, right = 16, top = 30, bottom = 44;
  const double plot_w = width - left - right, plot_h = height - top - bottom;
  AxisRange xr, yr;
  for (const ChartLine& line : chart.lines) {
    for (double v : line.x) xr.add(v);
    for (double v : line.y) yr.add(v);
  }
  xr = xr.padded();
  yr = yr.padded();
  auto px = [&](double x) { return left + (x - xr.low) / (xr.high - xr.low) * plot_w; };
  auto py = [&](double y) { return top + (yr.high - y) / (yr.high - yr.low) * plot_h; };

  std::string svg = fmt::format(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{0}\" height=\"{1}\" viewBox=\"0 0 {0} {1}\" "
      "font-family=\"sans-serif\" font-size=\"11\">\n<rect width=\"{0}\" height=\"{1}\" fill=\"white\"/>\n",
      width, height);
  svg += fmt::format("<text x=\"{}\" y=\"18\" font-size=\"13\" text-anchor=\"middle\">{}</text>\n", left + plot_w / 2,
                     escape_xml(chart.title));
  for (double t : round_ticks(xr.low, xr.high)) {
    svg += fmt::format("<line x1=\"{0:.1f}\" y1=\"{1:.1f}\" x2=\"{0:.1f}\" y2=\"{2:.1f}\" stroke=\"#ddd\"/>\n", px(t), top,
                       top + plot_h);
    svg += fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\" text-anchor=\"middle\">{:g}</text>\n", px(t), top + plot_h + 14, t);
  }
  for (double t : round_ticks(yr.low, yr.high)) {
    svg += fmt::format("<line x1=\"{0:.1f}\" y1=\"{1:.1f}\" x2=\"{2:.1f}\" y2=\"{1:.1f}\" stroke=\"#ddd\"/>\n", left, py(t),
                       left + plot_w);
    svg += fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\" text-anchor=\"end\">{:.4g}</text>\n", left - 4, py(t) + 4, t);
  }
  svg += fmt::format("<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"none\" stroke=\"#444\"/>\n", left, top,
                     plot_w, plot_h);
  svg += fmt::format("<text x=\"{:.1f}\" y=\"{}\" text-anchor=\"middle\">{}</text>\n", left + plot_w / 2, height - 6,
                     escape_xml(chart.x_label));
  svg += fmt::format("<text transform=\"translate(14 {:.1f}) rotate(-90)\" text-anchor=\"middle\">{}</text>\n",
                     top + plot_h / 2, escape_xml(chart.y_label));

  for (size_t i = 0; i < chart.lines.size(); ++i) {
    const ChartLine& line = chart.lines[i];
    const char* colour = kColours[i % std::size(kColours)];
    std::string path;
    bool pen_down = false;
    for (size_t k = 0; k < std::min(line.x.size(), line.y.size()); ++k) {
      if (!std::isfinite(line.x[k]) || !std::isfinite(line.y[k])) {
        pen_down = false;
        continue;
      }
      path += fmt::format("{}{:.2f},{:.2f} ", pen_down ? "L" : "M", px(line.x[k]), py(line.y[k]));
      pen_down = true;
    }
    // Later lines dashed, so a line drawn over an identical one still shows.
    svg += fmt::format("<path d=\"{}\" fill=\"none\" stroke=\"{}\" stroke-width=\"1.6\"{}/>\n", path, colour,
                       i == 0 ? "" : fmt::format(" stroke-dasharray=\"{} 3\"", 3 + 3 * i));
    const double ly = top + 14 + 14 * static_cast<double>(i);
    svg += fmt::format("<line x1=\"{0:.1f}\" y1=\"{1:.1f}\" x2=\"{2:.1f}\" y2=\"{1:.1f}\" stroke=\"{3}\" stroke-width=\"2\"/>\n",
                       left + plot_w - 90, ly, left + plot_w - 70, colour);
    svg += fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\">{}</text>\n", left + plot_w - 66, ly + 4, escape_xml(line.label));
  }
  svg += "</svg>\n";
  return svg;
}

}  // namespace moreau
