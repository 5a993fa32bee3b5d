#pragma once
// Helpers for tests that run scene files through the command line and read what they write.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "test_helpers.hpp"

namespace moreau::test {

inline std::string write_scene(const std::string& tag, const std::string& text) {
  const std::string path = temp_dir(tag) + "/scene.json";
  std::ofstream(path) << text;
  return path;
}

// probes.csv as rows of numbers (the header skipped).
inline std::vector<std::vector<Real>> read_probes(const std::string& dir) {
  std::ifstream in(dir + "/probes.csv");
  std::string line;
  std::getline(in, line);
  std::vector<std::vector<Real>> rows;
  while (std::getline(in, line)) {
    std::vector<Real> row;
    std::stringstream ss(line);
    std::string cell;
    while (std::getline(ss, cell, ',')) row.push_back(std::stod(cell));
    rows.push_back(row);
  }
  return rows;
}

// Runs a scene through the command line into `out` and returns its probe rows (none, with the
// failure recorded, if the run does not succeed).
inline std::vector<std::vector<Real>> run_scene(const std::string& scene, const std::string& out, const std::string& extra = "") {
  const auto r = run_moreau(fmt::format("run {} --out {} --quiet {}", scene, out, extra));
  EXPECT_EQ(r.exit_code, 0) << r.output;
  return r.exit_code == 0 ? read_probes(out) : std::vector<std::vector<Real>>{};
}

}  // namespace moreau::test
