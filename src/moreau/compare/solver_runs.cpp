#include "moreau/compare/solver_runs.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <fstream>
#include <set>
#include <sstream>

#include "moreau/io/frame_writer.hpp"
#include "moreau/moreau.hpp"
#include "moreau/scene/json_reader.hpp"
#include "moreau/solvers/solver_registry.hpp"

namespace moreau {

namespace {

// Per-object penetration columns are added for at most this many objects (a scene of a thousand
// boxes gets the overall column only).
constexpr size_t kMostPenetrationObjects = 12;

void check_solvers(const CompareOptions& options) {
  const std::vector<std::string> available = registered_solver_names();
  if (options.solvers.size() < 2)
    throw InputError(fmt::format("--solvers: give at least two of {} separated by commas, e.g. --solvers xpbd,nmd",
                                 fmt::join(available, ", ")));
  std::set<std::string> seen;
  for (const std::string& s : options.solvers) {
    if (std::find(available.begin(), available.end(), s) == available.end())
      throw InputError(fmt::format("--solvers: '{}' is not a constraint-engine solver; allowed: {}", s,
                                   fmt::join(available, ", ")));
    if (!seen.insert(s).second) throw InputError(fmt::format("--solvers: '{}' is given twice; give each solver once", s));
  }
}

// A JSON value's string, or "" when it is missing or not a string (the scene's own validation
// reports that when the scene loads).
std::string string_at(const nlohmann::json& object, const char* key) {
  return object.is_object() && object.contains(key) && object[key].is_string() ? object[key].get<std::string>() : "";
}

// A name that can head a CSV column of its own: no separator, quote, line break, or the '@'
// compare.csv puts between a column and its solver.
bool plain_column_name(const std::string& name) { return name.find_first_of(",\"\n\r@") == std::string::npos; }

// The probes of every run: the scene's own (after the overrides) and the comparison's.
nlohmann::json probes_with_comparison(const nlohmann::json& scene, const std::string& file) {
  nlohmann::json probes = scene.contains("probes") ? scene["probes"] : nlohmann::json::array();
  if (!probes.is_array()) throw InputError(fmt::format("{}: probes: expected an array of probes", file));
  std::set<std::string> names;
  for (const auto& p : probes) names.insert(string_at(p, "name"));
  auto add = [&](nlohmann::json probe) {
    const std::string name = probe["name"];
    if (names.count(name))
      throw InputError(fmt::format("{}: probes: the name '{}' is one moreau compare adds; rename that probe", file, name));
    probes.push_back(std::move(probe));
  };
  const std::string p = kComparisonPrefix;
  add({{"name", p + "energy"}, {"type", "energy"}, {"object", "*"}, {"quantity", "total"}});
  // Cloth's distance rows: a stretch in m, comparable between solvers (the other families'
  // errors are elastic strains, or angles).
  const bool cloth = scene.contains("objects") && scene["objects"].is_array() &&
                     std::any_of(scene["objects"].begin(), scene["objects"].end(),
                                 [](const nlohmann::json& o) { return string_at(o, "kind") == "cloth"; });
  if (cloth) add({{"name", p + "stretch"}, {"type", "constraint_error"}, {"object", "*"}, {"family", "distance"}});
  if (scene.contains("joints") && scene["joints"].is_array() && !scene["joints"].empty())
    add({{"name", p + "joint_error"}, {"type", "joint_error"}, {"joint", "*"}});
  add({{"name", p + "penetration"}, {"type", "penetration"}, {"object", "*"}});
  std::vector<std::string> touching;  // objects with contacts: not colliders (they cannot be named) or fluids
  if (scene.contains("objects") && scene["objects"].is_array())
    for (const auto& o : scene["objects"]) {
      const std::string kind = string_at(o, "kind"), name = string_at(o, "name");
      if (kind != "collider" && kind != "fluid" && !name.empty() && plain_column_name(name)) touching.push_back(name);
    }
  if (touching.size() <= kMostPenetrationObjects)
    for (const std::string& name : touching)
      add({{"name", p + std::string(kPenetrationOf) + name}, {"type", "penetration"}, {"object", name}});
  return probes;
}

std::vector<double> numbers_of(const std::string& line, const std::string& path, size_t row) {
  std::vector<double> numbers;
  std::stringstream in(line);
  std::string cell;
  while (std::getline(in, cell, ',')) {
    try {
      numbers.push_back(std::stod(cell));
    } catch (const std::exception&) {
      throw std::runtime_error(fmt::format("{}: row {}: '{}' is not a number", path, row, cell));
    }
  }
  return numbers;
}

}  // namespace

void read_probe_table(const std::string& path, SolverRun& run) {
  std::ifstream in(path);
  std::string line;
  if (!std::getline(in, line)) throw std::runtime_error(fmt::format("{}: no header", path));
  std::stringstream header(line);
  std::string cell;
  std::getline(header, cell, ',');  // time
  while (std::getline(header, cell, ',')) run.columns.push_back(cell);
  run.values.assign(run.columns.size(), {});
  for (size_t row = 1; std::getline(in, line); ++row) {
    const std::vector<double> numbers = numbers_of(line, path, row);
    if (numbers.size() != run.columns.size() + 1)
      throw std::runtime_error(fmt::format("{}: row {} has {} cells, not {}", path, row, numbers.size(), run.columns.size() + 1));
    run.time.push_back(numbers[0]);
    for (size_t c = 0; c < run.columns.size(); ++c) run.values[c].push_back(numbers[c + 1]);
  }
}

SolverRuns run_each_solver(const CompareOptions& options) {
  check_solvers(options);
  nlohmann::json scene = parse_json_file(options.scene_path);
  for (const std::string& o : options.overrides) apply_override(scene, o, options.scene_path);
  if (scene.is_object() && scene.contains("settings") && string_at(scene["settings"], "solver") == "fem")
    throw InputError(fmt::format("{}: settings.solver: moreau compare runs constraint-engine scenes (xpbd, nmd); "
                                 "this is a finite-element scene",
                                 options.scene_path));
  std::vector<std::string> overrides = options.overrides;
  overrides.push_back("probes=" + probes_with_comparison(scene, options.scene_path).dump());

  // Every scene is loaded (and so validated) before anything runs.
  std::vector<World> worlds;
  for (const std::string& solver : options.solvers) {
    std::vector<std::string> with_solver = overrides;
    with_solver.push_back("settings.solver=" + solver);
    worlds.push_back(World::load(options.scene_path, with_solver));
  }
  SolverRuns result;
  result.scene_name = worlds.front().name();
  result.out_dir = options.out_dir.empty() ? "out/" + safe_file_name(result.scene_name) + "-compare" : options.out_dir;
  writable_directory(result.out_dir);
  const std::string& out_dir = result.out_dir;
  std::vector<SolverRun>& runs = result.runs;
  for (size_t i = 0; i < worlds.size(); ++i) {
    SolverRun run;
    run.solver = options.solvers[i];
    RunOptions ro;
    ro.out_dir = out_dir + "/" + run.solver;
    ro.duration = options.duration;
    ro.threads = options.threads;
    ro.progress = options.progress;
    try {
      const RunResult r = worlds[i].run(ro);
      run.out_dir = r.out_dir;
    } catch (const NumericalError& e) {
      run.status = "failed";
      run.message = e.what();
      run.out_dir = ro.out_dir;
    }
    run.steps = worlds[i].steps();
    run.stage_times = worlds[i].stage_times();
    std::ifstream summary(run.out_dir + "/run.json");
    run.wall_time_s = nlohmann::json::parse(summary).at("wall_time_s").get<double>();
    read_probe_table(run.out_dir + "/probes.csv", run);
    runs.push_back(std::move(run));
  }
  return result;
}

}  // namespace moreau
