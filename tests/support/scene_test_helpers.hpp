#pragma once
// Helpers for tests that run scene files through the command line and read what they write.
#include <gtest/gtest.h>

#include <filesystem>
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

/// A scene file's path: `scene` names a file in scenes/, or (starting with '{') is the scene's JSON,
/// written to a file of its own.
inline std::string scene_path(const std::string& scene) {
  if (scene.starts_with('{')) return write_scene("inline-scene", scene);
  return (std::filesystem::path(MOREAU_SOURCE_DIR) / "scenes" / scene).string();
}

// A transient flow small enough for a test: the lid-driven cavity on 16 x 16 cells by BDF2.
inline constexpr const char* kTransientCavity = R"({"name": "transient_cavity",
  "settings": {"solver": "fem", "integrator": "bdf2", "dt": 0.05, "gravity": [0, 0, 0]},
  "objects": [{"name": "fluid", "kind": "fluid", "mesh": {"type": "rectangle", "min": [0, 0], "max": [1, 1], "cells": [16, 16]},
               "density": 1.0, "viscosity": 0.01,
               "boundaries": [{"where": {"side": "top"}, "velocity": ["1", "0"]},
                              {"where": {"side": ["left", "right", "bottom"]}, "type": "no_slip"}],
               "pressure_reference": {"mean": 0}}],
  "probes": [{"name": "centre", "type": "point", "at": [0.5, 0.5]},
             {"name": "lid_force", "type": "boundary_force", "where": {"side": "top"}}]})";


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

/// Runs a scene that must be refused: exit code 2, each of `needles` in the message, and no output
/// directory left behind.
inline void expect_bad_scene(const std::string& tag, const std::string& text, const std::vector<std::string>& needles) {
  const std::string path = write_scene(tag, text);
  const std::string out = std::filesystem::path(path).parent_path() / "out";
  const auto r = run_moreau(fmt::format("run {} --out {} --quiet", path, out));
  EXPECT_EQ(r.exit_code, 2) << r.output;
  for (const auto& n : needles) EXPECT_NE(r.output.find(n), std::string::npos) << "missing '" << n << "' in: " << r.output;
  EXPECT_FALSE(std::filesystem::exists(out)) << "bad input must not leave output behind";
}

}  // namespace moreau::test
