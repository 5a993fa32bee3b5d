// Scene files: JSON text or a file, with the command line's overrides applied, read into specs
// (spec_builders.hpp) and built by assemble_scene; "solver": "fem" scenes go to the FEM builders.
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <filesystem>

#include "moreau/errors.hpp"
#include "moreau/math/fnv1a.hpp"
#include "moreau/scene/fem_scene.hpp"
#include "moreau/scene/spec_builders.hpp"
#include "moreau/scene/scene.hpp"
#include "moreau/scene/scene_assembly.hpp"

namespace moreau {

namespace {

// "solver": "fem" scenes: the FEM engine reads its own keys (allow_fem_settings); the constraint
// engine's ones would be accepted and ignored, so they are not offered.
void read_fem_settings(const JsonObject& settings, Scene& scene) {
  scene.solver = "fem";
  scene.fem = std::make_unique<FemProblem>();
  allow_fem_settings(settings);
  scene.fem->dt = settings.number("dt", scene.fem->dt, Range::positive());
  scene.duration = settings.number("duration", scene.duration, Range::positive());
  scene.model.settings.gravity = settings.vec3("gravity", scene.model.settings.gravity);
  scene.model.settings.threads = settings.integer("threads", scene.model.settings.threads, 0, 1024);
  read_output_settings(settings, scene.output.every, scene.output.formats, scene.output.checkpoint_every, false);
  settings.finish();
}

Scene build_fem_scene_file(const JsonObject& top, const JsonObject& settings, const std::string& path, std::string name) {
  Scene scene;
  scene.file = path;
  scene.name = std::move(name);
  read_fem_settings(settings, scene);
  build_fem_scene(top, *scene.fem, scene.model.settings.gravity, scene.model.settings.threads);
  top.finish();
  return scene;
}

// One object of "objects", read into its kind's spec.
ObjectSpec read_object(const JsonObject& object) {
  const std::string name = object.string("name");
  const std::string kind = object.choice("kind", {"collider", "cloth", "soft_body", "fluid", "rigid_body", "rod", "granular", "shape_matched", "continuum"});
  ObjectSpec spec;
  if (kind == "collider") spec = read_collider(object);
  else if (kind == "rigid_body") spec = read_rigid_body(object);
  else if (kind == "cloth") spec = read_cloth(object);
  else if (kind == "fluid") spec = read_fluid(object);
  else if (kind == "rod") spec = read_rod(object);
  else if (kind == "granular") spec = read_granular(object);
  else if (kind == "shape_matched") spec = read_shape_matched(object);
  else if (kind == "continuum") spec = read_continuum(object);
  else spec = read_soft_body(object);
  std::visit([&](auto& s) { s.name = name; }, spec);
  object.finish();
  return spec;
}

// Validates and builds the scene in `root` (read from `path`, overrides applied).
Scene build_scene_from_json(const nlohmann::json& root, const std::string& path) {
  const JsonObject top(root, "", path);
  SceneSpec spec;
  spec.name = top.string("name");
  if (spec.name.empty()) top.fail("name", "the scene name must not be empty");
  top.allow("description");
  const auto settings = top.optional_object("settings");
  if (settings && settings->has("solver") && settings->string("solver") == "fem")
    return build_fem_scene_file(top, *settings, path, spec.name);

  if (settings) spec.settings = read_settings(*settings);
  for (const JsonObject& object : top.object_list("objects")) {
    spec.objects.push_back(read_object(object));
  }
  for (const JsonObject& joint : top.object_list("joints")) {
    spec.joints.push_back(read_joint(joint));
  }
  for (const JsonObject& probe : top.object_list("probes")) {
    spec.probes.push_back(read_probe(probe));
  }
  top.finish();
  return assemble_scene(spec, path, path, std::filesystem::absolute(path).parent_path());
}


// FNV-1a (64 bit) of the scene's JSON with the keys that only shape a run removed: the same
// physics gives the same fingerprint, whatever the duration, output or thread count.
std::string scene_fingerprint(nlohmann::json root) {
  if (root.is_object()) {
    root.erase("description");
    if (root.contains("settings") && root["settings"].is_object())
      for (const char* key : {"duration", "output", "threads"}) root["settings"].erase(key);
  }
  return fmt::format("{:016x}", fnv1a(root.dump()));
}

// Validates and builds the scene in `root` (read from `path`) after applying the overrides.
Scene build_scene(nlohmann::json root, const std::string& path, const std::vector<std::string>& overrides) {
  for (const auto& o : overrides) apply_override(root, o, path);
  Scene scene = build_scene_from_json(root, path);
  scene.fingerprint = scene_fingerprint(std::move(root));
  return scene;
}

}  // namespace

Scene load_scene(const std::string& path, const std::vector<std::string>& overrides) {
  return build_scene(parse_json_file(path), path, overrides);
}

Scene load_scene_text(const std::string& text, const std::string& source, const std::vector<std::string>& overrides) {
  return build_scene(parse_json_text(text, source), source, overrides);
}

}  // namespace moreau
