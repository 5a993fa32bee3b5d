// SceneBuilder (include/moreau/scene_builder.hpp): specs given in code, checked and built by the
// same assemble_scene as a scene file.
#include "moreau/scene_builder.hpp"

#include <fmt/format.h>

#include <filesystem>

#include "moreau/scene/scene_assembly.hpp"

namespace moreau {

SceneBuilder::SceneBuilder(std::string name) : name_(std::move(name)) {}

SceneBuilder& SceneBuilder::add(ObjectSpec object) {
  objects_.push_back(std::move(object));
  return *this;
}

SceneBuilder& SceneBuilder::add(JointSpec joint) {
  joints_.push_back(std::move(joint));
  return *this;
}

SceneBuilder& SceneBuilder::add(ProbeSpec probe) {
  probes_.push_back(std::move(probe));
  return *this;
}

World SceneBuilder::build() const {
  // Messages name the scene and the entry as a scene file would: objects[2].material.density.
  const SceneSpec spec{name_, settings_, objects_, joints_, probes_};
  const std::string source = fmt::format("scene '{}'", name_);
  return World(std::make_unique<Scene>(assemble_scene(spec, source, "(built in code)", std::filesystem::current_path())));
}

}  // namespace moreau
