#pragma once
// The one path from specs to a Scene: a scene file is read into specs (scene_loader.cpp), a
// SceneBuilder holds them from code, and both end here.
#include <filesystem>
#include <string>
#include <vector>

#include "moreau/scene/scene.hpp"
#include "moreau/scene/spec_place.hpp"
#include "moreau/scene_builder.hpp"

namespace moreau {

/// A whole constraint-engine scene as specs.
struct SceneSpec {
  std::string name;
  SceneSettings settings;
  std::vector<ObjectSpec> objects;
  std::vector<JointSpec> joints;
  std::vector<ProbeSpec> probes;
};

/// Checks and builds the scene. Problems are InputErrors "{source}: {path}: ...", the path
/// that of the scene format (settings.dt, objects[2].mass, joints[0].axis, probes[1].object), so
/// a file's errors name its JSON paths. `file` names the scene in run.json; relative mesh paths
/// are resolved against `scene_directory`.
Scene assemble_scene(const SceneSpec& spec, const std::string& source, const std::string& file,
                     const std::filesystem::path& scene_directory);

}  // namespace moreau
