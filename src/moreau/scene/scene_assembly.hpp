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

/// A whole constraint-engine scene as specs, each with the place it came from.
struct SceneSpec {
  std::string name;
  SceneSettings settings;
  std::vector<ObjectSpec> objects;
  std::vector<JointSpec> joints;
  std::vector<ProbeSpec> probes;
};

struct SceneSpecPlaces {
  SpecPlace top, settings;
  std::vector<SpecPlace> objects, joints, probes;  // one per spec
};

/// Checks and builds the scene; `file` names it in run.json, relative mesh paths are resolved
/// against `scene_directory`. Throws InputError at the first problem.
Scene assemble_scene(const SceneSpec& spec, const SceneSpecPlaces& places, const std::string& file,
                     const std::filesystem::path& scene_directory);

}  // namespace moreau
