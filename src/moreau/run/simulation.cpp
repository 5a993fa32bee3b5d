// moreau::Simulation, the public API: a loaded scene and the engine that steps it; run() is the one
// run loop (run_loop.cpp).
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

Simulation::Simulation(std::unique_ptr<Scene> scene) : scene_(std::move(scene)), engine_(make_engine(*scene_)) {}
Simulation::~Simulation() = default;
Simulation::Simulation(Simulation&&) noexcept = default;
Simulation& Simulation::operator=(Simulation&&) noexcept = default;

Simulation Simulation::load(const std::string& scene_path, const std::vector<std::string>& overrides) {
  return Simulation(std::make_unique<Scene>(load_scene(scene_path, overrides)));
}

const std::string& Simulation::name() const { return scene_->name; }
Scene& Simulation::internals() { return *scene_; }
double Simulation::time() const { return engine_->time(); }
std::string Simulation::summary() const { return engine_->summary(); }

void Simulation::step() {
  const int requested = engine_->requested_threads();
  engine_->step(requested > 0 ? requested : omp_get_max_threads());
}

std::vector<double> Simulation::position(const std::string& object, int vertex) const {
  const Index o = scene_->model.find_object(object);
  if (o < 0 || vertex < 0 || vertex >= scene_->model.objects[o].particle_count())
    throw InputError(fmt::format("no vertex {} in object '{}'", vertex, object));
  const Vec3& x = scene_->state.position[scene_->model.objects[o].particle_begin + vertex];
  return {x.x(), x.y(), x.z()};
}

RunResult Simulation::run(const RunOptions& options) { return run_engine(*engine_, *scene_, options); }

}  // namespace moreau
