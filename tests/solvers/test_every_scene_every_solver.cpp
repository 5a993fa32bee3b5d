// Every scene of scenes/ and bench/scenes/ under every formulation that accepts it: the
// constraint engine's registered solvers (settings.solver) for constraint scenes, the FEM engine
// for "solver": "fem" scenes. A new scene or a newly registered solver is covered without editing
// this file. For each pair, a few steps on one thread and on two must give the same bits in every
// state array and every probe (the engine's promise: results do not depend on the thread count),
// and every state value must stay finite (a probe may be nan: the extent of a fluid whose emitter
// has not released a particle yet). A formulation refuses a scene that holds what it does not
// simulate (solver_registry.hpp): such a pair checks the refusal instead — exit 2 at
// settings.solver, naming what the scene holds — and only where this file expects one.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <ostream>

#include <nlohmann/json.hpp>

#include "moreau/errors.hpp"
#include "moreau/solvers/solver_registry.hpp"
#include "moreau/world.hpp"

namespace moreau {
namespace {

namespace fs = std::filesystem;

struct ScenePair {
  std::string scene;   // path relative to the repository
  std::string solver;  // "xpbd", ..., or "fem"
};

// How ctest and gtest name a pair (not its bytes).
void PrintTo(const ScenePair& pair, std::ostream* out) { *out << pair.scene << " under " << pair.solver; }

// Scenes whose full size would take minutes for no extra coverage run smaller here (the same
// keys, coarser meshes, fewer continuation stages).
const std::map<std::string, std::vector<std::string>> kSmaller = {
    {"scenes/cavity_re1000.json", {"objects.fluid.mesh.cells=[16,16]", "objects.fluid.continuation.viscosity=[0.01]"}},
    {"scenes/cavity3d_re400.json", {"objects.fluid.mesh.cells=[4,4,4]"}},
    {"scenes/cylinder_re20.json", {"objects.fluid.mesh.parameters.N=1"}},
    {"scenes/cylinder_re100.json", {"objects.fluid.mesh.parameters.N=1"}},
    {"scenes/cylinder_re20_immersed.json", {"objects.fluid.mesh.parameters.N=8", "objects.cylinder.mesh.parameters.n=8"}},
    {"bench/scenes/fem_block_20.json", {"objects.block.mesh.cells=[4,4,4]"}},
    {"bench/scenes/sand_column_100k.json", {"objects.sand.spacing=0.0125"}},
    {"scenes/fluttering_plate.json", {"objects.water.mesh.cells=[24,64]"}},
    {"scenes/sedimenting_disc.json", {"objects.water.mesh.cells=[32,96]"}},
    {"scenes/turek_hron_fsi1.json",
     {"objects.fluid.mesh.parameters.N=2", "objects.bar.mesh.parameters.NX=18", "objects.bar.mesh.parameters.NY=2"}},
    {"scenes/turek_hron_fsi2.json",
     {"objects.fluid.mesh.parameters.N=2", "objects.bar.mesh.parameters.NX=18", "objects.bar.mesh.parameters.NY=2"}},
    {"scenes/two_leaflet_valve.json",
     {"objects.blood.mesh.cells=[64,16]", "objects.top_leaflet.mesh.cells=[2,10]", "objects.bottom_leaflet.mesh.cells=[2,10]"}},
};

std::vector<ScenePair> every_pair() {
  std::vector<ScenePair> pairs;
  const fs::path root(MOREAU_SOURCE_DIR);
  std::vector<fs::path> files;
  for (const char* dir : {"scenes", "bench/scenes"})
    for (const auto& entry : fs::directory_iterator(root / dir))
      if (entry.path().extension() == ".json") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  for (const fs::path& file : files) {
    const nlohmann::json scene = nlohmann::json::parse(std::ifstream(file));
    const std::string relative = fs::relative(file, root).string();
    const std::string solver = scene.contains("settings") ? scene["settings"].value("solver", "xpbd") : "xpbd";
    if (solver == "fem") {
      pairs.push_back({relative, "fem"});
      continue;
    }
    for (const std::string& name : registered_solver_names()) pairs.push_back({relative, name});
  }
  return pairs;
}

// The refusals expected: a formulation and what a scene it refuses holds (an object key,
// "key=value" for an object whose key has that string value, or "key.inner" for an object whose
// key holds an object with the key inner).
struct ExpectedRefusal {
  std::string solver, reason, key;
};
const std::vector<ExpectedRefusal> kRefusals = {{"xpbd", "does not simulate suction cups", "suction"},
                                                {"xpbi", "does not simulate suction cups", "suction"},
                                                {"xpbd", "does not simulate continua", "kind=continuum"},
                                                {"nmd", "does not simulate continua", "kind=continuum"},
                                                {"nmd", "does not simulate melting", "thermal.melting_point"}};

bool holds_key(const std::string& scene, const std::string& key) {
  const nlohmann::json json = nlohmann::json::parse(std::ifstream(fs::path(MOREAU_SOURCE_DIR) / scene));
  const size_t equals = key.find('=');
  const std::string name = key.substr(0, equals);
  const size_t dot = key.find('.');
  for (const auto& object : json.value("objects", nlohmann::json::array())) {
    if (dot != std::string::npos) {
      const std::string outer = key.substr(0, dot);
      if (object.contains(outer) && object[outer].is_object() && object[outer].contains(key.substr(dot + 1))) return true;
      continue;
    }
    if (!object.contains(name)) continue;
    if (equals == std::string::npos) return true;
    if (object[name].is_string() && object[name].get<std::string>() == key.substr(equals + 1)) return true;
  }
  return false;
}

// The refusal this file expects for the pair, or nullptr.
const ExpectedRefusal* expected_refusal(const ScenePair& pair) {
  for (const ExpectedRefusal& r : kRefusals)
    if (r.solver == pair.solver && holds_key(pair.scene, r.key)) return &r;
  return nullptr;
}

// The state after `steps` steps on `threads` threads: every array's values, then the probes.
std::map<std::string, std::vector<double>> state_after(const ScenePair& pair, int steps, int threads) {
  std::vector<std::string> overrides;
  if (auto smaller = kSmaller.find(pair.scene); smaller != kSmaller.end()) overrides = smaller->second;
  if (pair.solver != "fem") overrides.push_back("settings.solver=\"" + pair.solver + "\"");
  World world = World::load((fs::path(MOREAU_SOURCE_DIR) / pair.scene).string(), overrides);
  // A steady flow is solved whole in one step.
  const int count = world.dt() > 0 ? steps : 1;
  for (int s = 0; s < count; ++s) world.step(threads);
  std::map<std::string, std::vector<double>> state;
  for (const StateArray& a : world.arrays()) state[a.name].assign(a.values.begin(), a.values.end());
  const std::vector<std::string> names = world.probe_names();
  const std::vector<double> probes = world.probe_values();
  for (size_t k = 0; k < probes.size(); ++k) state["probe " + names[k]] = {probes[k]};
  return state;
}

class EverySceneEverySolver : public ::testing::TestWithParam<ScenePair> {};

TEST_P(EverySceneEverySolver, RunsFiniteAndIndependentOfTheThreadCount) {
  const ScenePair& pair = GetParam();
  if (const ExpectedRefusal* refusal = expected_refusal(pair)) {
    try {
      World::load((fs::path(MOREAU_SOURCE_DIR) / pair.scene).string(), {"settings.solver=\"" + pair.solver + "\""});
      ADD_FAILURE() << pair.scene << " under " << pair.solver << " was expected to be refused: " << refusal->reason;
    } catch (const InputError& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find("settings.solver"), std::string::npos) << message;
      EXPECT_NE(message.find(refusal->reason), std::string::npos) << message;
    }
    return;
  }
  const int steps = 3;
  const auto one = state_after(pair, steps, 1), two = state_after(pair, steps, 2);
  ASSERT_FALSE(one.empty());
  ASSERT_EQ(one.size(), two.size());
  for (const auto& [name, values] : one) {
    const std::vector<double>& other = two.at(name);
    ASSERT_EQ(values.size(), other.size()) << name;
    if (!name.starts_with("probe ")) {
      for (size_t k = 0; k < values.size(); ++k) ASSERT_TRUE(std::isfinite(values[k])) << name << " value " << k;
    }
    // Bits, not a tolerance: the same operations in the same order on any thread count.
    EXPECT_TRUE(values.empty() || std::memcmp(values.data(), other.data(), values.size() * sizeof(double)) == 0)
        << name << " of " << pair.scene << " under " << pair.solver << " differs between one and two threads";
  }
}

std::string pair_name(const ::testing::TestParamInfo<ScenePair>& info) {
  std::string name = fs::path(info.param.scene).parent_path().string() + "_" + fs::path(info.param.scene).stem().string() +
                     "_" + info.param.solver;
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return name;
}

INSTANTIATE_TEST_SUITE_P(Scenes, EverySceneEverySolver, ::testing::ValuesIn(every_pair()), pair_name);

}  // namespace
}  // namespace moreau
