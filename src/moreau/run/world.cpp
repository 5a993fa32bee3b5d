// moreau::World, the public API: a loaded scene and the engine that steps it; run() is the one
// run loop (run_loop.cpp).
#include "moreau/world.hpp"

#include <fmt/format.h>
#include <omp.h>

#include "moreau/moreau.hpp"
#include "moreau/run/engine.hpp"
#include "moreau/run/run_loop.hpp"
#include "moreau/scene/memory_estimate.hpp"
#include "moreau/scene/scene.hpp"

namespace moreau {

const char* version() { return MOREAU_VERSION; }

void set_memory_limit(double bytes) { set_memory_limit_bytes(bytes); }

World::World(std::unique_ptr<Scene> scene)
    : scene_(std::move(scene)), engine_(make_engine(*scene_)),
      identity_(std::make_unique<CheckpointHeader>(checkpoint_identity(*scene_, *engine_))) {}
World::~World() = default;
World::World(World&&) noexcept = default;
World& World::operator=(World&&) noexcept = default;

World World::load(const std::string& scene_path, const std::vector<std::string>& overrides) {
  return World(std::make_unique<Scene>(load_scene(scene_path, overrides)));
}

World World::from_json(const std::string& scene_json, const std::vector<std::string>& overrides) {
  return World(std::make_unique<Scene>(load_scene_text(scene_json, "(scene JSON)", overrides)));
}

const std::string& World::name() const { return scene_->name; }
std::string World::engine() const { return engine_->name(); }
std::string World::summary() const { return engine_->summary(); }
std::vector<WorldObject> World::objects() const { return engine_->objects(); }
double World::time() const { return engine_->time(); }
double World::dt() const { return engine_->dt(); }
long World::steps() const { return steps_; }

void World::step() {
  const int requested = engine_->requested_threads();
  step(requested > 0 ? requested : omp_get_max_threads());
}

void World::step(int threads) {
  engine_->step(std::max(1, threads));
  ++steps_;
}

RunResult World::run(const RunOptions& options) {
  const std::unique_ptr<RestartPoint> restart = std::move(restart_);  // continued by this run only
  return run_engine(*engine_, *scene_, options, {*identity_, restart.get(), steps_});
}

void World::save_checkpoint(const std::string& path) const {
  CheckpointHeader header = *identity_;
  header.time = engine_->time();
  header.steps = steps_;
  write_checkpoint(path, header, *engine_);
}

void World::restore(const std::string& path) {
  CheckpointHeader header = read_checkpoint(path, *identity_, *engine_);
  steps_ = header.steps;
  restart_ = std::make_unique<RestartPoint>(RestartPoint{path, std::move(header)});
}

std::vector<StateArray> World::arrays() { return engine_->state_arrays(); }

StateArray World::array(const std::string& name) {
  std::vector<StateArray> all = arrays();
  std::string names;
  for (StateArray& a : all) {
    if (a.name == name) return a;
    names += (names.empty() ? "" : ", ") + a.name;
  }
  throw InputError(fmt::format("scene '{}' has no state array '{}'; its {} engine has: {}", scene_->name, name,
                               engine_->name(), names));
}

std::vector<std::string> World::probe_names() const { return engine_->probe_columns(); }

std::vector<double> World::probe_values() const {
  std::vector<Real> values;
  engine_->sample_probes(values);
  return values;
}

std::map<std::string, double> World::stage_times() const { return engine_->stage_times(); }

}  // namespace moreau
