#include "moreau/compare/comparison_report.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

#include "moreau/compare/svg_chart.hpp"
#include "moreau/io/frame_writer.hpp"

namespace moreau {

namespace {

using Row = std::vector<std::string>;

struct Table {
  Row header;
  std::vector<Row> rows;
};

std::string markdown_table(const Table& t) {
  auto line = [](const Row& cells) {
    std::string s = "|";
    for (const std::string& c : cells) {
      std::string cell;
      for (char ch : c) cell += ch == '|' ? std::string("\\|") : std::string(1, ch);
      s += " " + cell + " |";
    }
    return s + "\n";
  };
  std::string s = line(t.header) + "|";
  for (size_t i = 0; i < t.header.size(); ++i) s += i == 0 ? "---|" : "---:|";
  s += "\n";
  for (const Row& r : t.rows) s += line(r);
  return s;
}

// Markdown's `code` spans become <code> in the HTML twin.
std::string html_cell(const std::string& text) {
  std::string out;
  bool in_code = false;
  for (char c : escape_xml(text)) {
    if (c == '`') {
      out += in_code ? "</code>" : "<code>";
      in_code = !in_code;
    } else {
      out += c;
    }
  }
  return out;
}

std::string html_table(const Table& t) {
  std::string s = "<table>\n<tr>";
  for (const std::string& c : t.header) s += "<th>" + html_cell(c) + "</th>";
  s += "</tr>\n";
  for (const Row& r : t.rows) {
    s += "<tr>";
    for (size_t i = 0; i < r.size(); ++i) s += (i == 0 ? "<td>" : "<td class=\"n\">") + html_cell(r[i]) + "</td>";
    s += "</tr>\n";
  }
  return s + "</table>\n";
}

std::string number(double v) { return std::isfinite(v) ? fmt::format("{:.6g}", v) : "–"; }

// A column's index in a run, or -1.
int column_of(const SolverRun& run, const std::string& name) {
  const auto it = std::find(run.columns.begin(), run.columns.end(), name);
  return it == run.columns.end() ? -1 : static_cast<int>(it - run.columns.begin());
}

double largest(const std::vector<double>& v) {
  double m = -std::numeric_limits<double>::infinity();
  for (double x : v)
    if (std::isfinite(x)) m = std::max(m, x);
  return m;
}

// The largest |a - b| over the rows both runs reached (non-finite entries skipped).
double largest_difference(const std::vector<double>& a, const std::vector<double>& b) {
  double m = std::numeric_limits<double>::quiet_NaN();
  for (size_t k = 0; k < std::min(a.size(), b.size()); ++k)
    if (std::isfinite(a[k]) && std::isfinite(b[k])) m = std::isnan(m) ? std::abs(a[k] - b[k]) : std::max(m, std::abs(a[k] - b[k]));
  return m;
}

// Per run, one cell from a column (or "–" when the run has no such column).
Row column_row(const std::string& label, const std::vector<SolverRun>& runs, const std::string& column,
               double (*of)(const std::vector<double>&)) {
  Row r{label};
  for (const SolverRun& run : runs) {
    const int c = column_of(run, column);
    r.push_back(c < 0 || run.values[c].empty() ? "–" : number(of(run.values[c])));
  }
  return r;
}

double first_value(const std::vector<double>& v) { return v.front(); }
double last_value(const std::vector<double>& v) { return v.back(); }
double largest_rise(const std::vector<double>& v) {
  if (!std::isfinite(v.front())) return std::numeric_limits<double>::quiet_NaN();
  double m = 0;
  for (double x : v)
    if (std::isfinite(x)) m = std::max(m, x - v.front());
  return m;
}

std::string stage_summary(const SolverRun& run) {
  std::vector<std::pair<double, std::string>> stages;
  for (const auto& [name, seconds] : run.stage_times) stages.push_back({seconds, name});
  std::sort(stages.rbegin(), stages.rend());
  std::string s;
  for (size_t i = 0; i < std::min<size_t>(3, stages.size()); ++i)
    s += fmt::format("{}{} {:.3g}", i ? ", " : "", stages[i].second, 1e3 * stages[i].first / std::max(run.steps, 1L));
  return s;
}

Table summary_table(const std::vector<SolverRun>& runs) {
  Table t;
  t.header = {""};
  for (const SolverRun& run : runs) t.header.push_back("`" + run.solver + "`");
  auto per_run = [&](const std::string& label, auto cell) {
    Row r{label};
    for (const SolverRun& run : runs) r.push_back(cell(run));
    t.rows.push_back(r);
  };
  const std::string p = kComparisonPrefix;
  per_run("status", [](const SolverRun& r) { return r.status; });
  per_run("steps", [](const SolverRun& r) { return std::to_string(r.steps); });
  per_run("wall time per step (ms)",
          [](const SolverRun& r) { return fmt::format("{:.3g}", 1e3 * r.wall_time_s / std::max(r.steps, 1L)); });
  per_run("slowest stages (ms per step)", stage_summary);
  t.rows.push_back(column_row("total energy at the start (J)", runs, p + "energy", first_value));
  t.rows.push_back(column_row("total energy at the end (J)", runs, p + "energy", last_value));
  t.rows.push_back(column_row("largest energy gain over the start (J)", runs, p + "energy", largest_rise));
  if (column_of(runs.front(), p + "stretch") >= 0)
    t.rows.push_back(column_row("largest stretch of a distance row (m)", runs, p + "stretch", largest));
  if (column_of(runs.front(), p + "joint_error.position") >= 0) {
    t.rows.push_back(column_row("largest joint error (m)", runs, p + "joint_error.position", largest));
    t.rows.push_back(column_row("largest joint error (rad)", runs, p + "joint_error.angle", largest));
  }
  t.rows.push_back(column_row("deepest penetration (m)", runs, p + "penetration", largest));
  for (const std::string& c : runs.front().columns)
    if (c.rfind(p + std::string(kPenetrationOf), 0) == 0)
      t.rows.push_back(column_row(fmt::format("deepest penetration of `{}` (m)", c.substr(p.size() + kPenetrationOf.size())),
                                  runs, c, largest));
  return t;
}

Table probe_table(const std::vector<SolverRun>& runs, const std::vector<std::string>& columns) {
  Table t;
  t.header = {"column"};
  for (const SolverRun& run : runs) t.header.push_back("`" + run.solver + "` at the end");
  for (size_t i = 1; i < runs.size(); ++i)
    t.header.push_back(fmt::format("largest |`{}` − `{}`|", runs[i].solver, runs[0].solver));
  for (const std::string& c : columns) {
    Row r = column_row("`" + c + "`", runs, c, last_value);
    const int c0 = column_of(runs[0], c);
    for (size_t i = 1; i < runs.size(); ++i) {
      const int ci = column_of(runs[i], c);
      r.push_back(c0 < 0 || ci < 0 ? "–" : number(largest_difference(runs[i].values[ci], runs[0].values[c0])));
    }
    t.rows.push_back(r);
  }
  return t;
}

std::string chart_of(const std::vector<SolverRun>& runs, const std::string& column) {
  LineChart chart{column, "time (s)", column, {}};
  for (const SolverRun& run : runs) {
    const int c = column_of(run, column);
    if (c >= 0) chart.lines.push_back({run.solver, run.time, run.values[c]});
  }
  return svg_line_chart(chart);
}

// compare.csv: time, then each column of each run ("<column>@<solver>"); a run that stopped
// early leaves its later cells empty. Every run samples at the same output steps.
void write_csv(const std::string& path, const std::vector<SolverRun>& runs) {
  const SolverRun* longest = &runs.front();
  for (const SolverRun& run : runs)
    if (run.time.size() > longest->time.size()) longest = &run;
  std::ofstream out(path);
  out << "time";
  for (const SolverRun& run : runs)
    for (const std::string& c : run.columns) out << ',' << c << '@' << run.solver;
  out << '\n';
  for (size_t k = 0; k < longest->time.size(); ++k) {
    out << fmt::format("{:.9g}", longest->time[k]);
    for (const SolverRun& run : runs)
      for (size_t c = 0; c < run.columns.size(); ++c)
        out << (k < run.values[c].size() ? fmt::format(",{:.17g}", run.values[c][k]) : ",");
    out << '\n';
  }
}

}  // namespace

std::pair<std::string, std::string> write_comparison_report(const ComparisonSubject& subject,
                                                            const std::vector<SolverRun>& runs) {
  namespace fs = std::filesystem;
  const std::string dir = subject.out_dir;
  // An earlier comparison's plots (NN_<column>.svg) go; anything else in plots/ stays.
  fs::create_directories(dir + "/plots");
  for (const auto& entry : fs::directory_iterator(dir + "/plots")) {
    const std::string file = entry.path().filename().string();
    if (entry.path().extension() == ".svg" && file.size() > 3 && std::isdigit(file[0]) && std::isdigit(file[1]) && file[2] == '_')
      fs::remove(entry.path());
  }
  write_csv(dir + "/compare.csv", runs);

  std::vector<std::string> scene_columns, comparison_columns;
  for (const std::string& c : runs.front().columns)
    (c.rfind(kComparisonPrefix, 0) == 0 ? comparison_columns : scene_columns).push_back(c);

  std::string solvers;
  for (size_t i = 0; i < runs.size(); ++i)
    solvers += (i == 0 ? "" : i + 1 == runs.size() ? " and " : ", ") + ("`" + runs[i].solver + "`");
  const std::string title = fmt::format("`{}` under {}", subject.scene_name, solvers);
  std::string intro = fmt::format(
      "Scene `{}`, run once per solver with the same settings; each run's full output (run.json, probes.csv, "
      "frames for ParaView) is in its own directory: ",
      subject.scene_file);
  for (size_t i = 0; i < runs.size(); ++i) intro += fmt::format("{}`{}/`", i ? ", " : "", runs[i].solver);
  intro += ". `compare.csv` holds every column of every run side by side. Energies include every dynamic object "
           "(kinetic, gravitational and elastic); contacts, friction and damping only take energy out, so without "
           "motors, kinematic bodies or moving colliders a gain over the start is a solver's artefact. Penetration is the deepest overlap of the detected contacts at "
           "each output step.";
  std::vector<std::string> failures;
  for (const SolverRun& run : runs)
    if (run.status != "completed") failures.push_back(fmt::format("`{}` stopped: {}", run.solver, run.message));

  const Table summary = summary_table(runs);
  const Table probes = probe_table(runs, scene_columns);
  const Table diagnostics = probe_table(runs, comparison_columns);

  std::string md = "# " + title + "\n\n" + intro + "\n\n";
  for (const std::string& f : failures) md += "**" + f + "**\n\n";
  md += "## Summary\n\n" + markdown_table(summary) + "\n";
  std::string html = "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>" + escape_xml(subject.scene_name) +
                     " compared</title>\n<style>body{font-family:sans-serif;max-width:1000px;margin:2em auto;}"
                     "table{border-collapse:collapse;margin:1em 0;}td,th{border:1px solid #bbb;padding:3px 8px;}"
                     "td.n{text-align:right;font-variant-numeric:tabular-nums;}</style></head><body>\n";
  html += "<h1>" + html_cell(title) + "</h1>\n<p>" + html_cell(intro) + "</p>\n";
  for (const std::string& f : failures) html += "<p><strong>" + html_cell(f) + "</strong></p>\n";
  html += "<h2>Summary</h2>\n" + html_table(summary);

  int plot_count = 0;
  auto section = [&](const std::string& heading, const Table& table, const std::vector<std::string>& columns) {
    if (columns.empty()) return;
    md += "## " + heading + "\n\n" + markdown_table(table) + "\n";
    html += "<h2>" + heading + "</h2>\n" + html_table(table);
    for (size_t i = 0; i < columns.size(); ++i) {
      const std::string svg = chart_of(runs, columns[i]);
      const std::string file = fmt::format("plots/{:02d}_{}.svg", plot_count++, safe_file_name(columns[i]));
      std::ofstream(dir + "/" + file) << svg;
      md += fmt::format("![{}]({})\n", columns[i], file);
      html += svg;
    }
    md += "\n";
  };
  section("The scene's probes", probes, scene_columns);
  section("Energy, constraint error and penetration", diagnostics, comparison_columns);
  html += "</body></html>\n";

  const std::string md_path = dir + "/report.md", html_path = dir + "/report.html";
  std::ofstream(md_path) << md;
  std::ofstream(html_path) << html;
  return {md_path, html_path};
}

}  // namespace moreau
