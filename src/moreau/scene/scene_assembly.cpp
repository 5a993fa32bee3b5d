#include "moreau/scene/scene_assembly.hpp"

#include <fmt/format.h>

#include "moreau/scene/spec_builders.hpp"
#include "moreau/solvers/solver_registry.hpp"

namespace moreau {

namespace {

const std::string& object_name(const ObjectSpec& object) {
  return std::visit([](const auto& spec) -> const std::string& { return spec.name; }, object);
}

// A collider removed at a time (`until`) is dropped from the particle contacts only: a scene
// whose fluids, rigid bodies, rods or suction cups would also meet it is refused.
template <class Entry>
void check_removed_colliders(const Model& model, const Entry& entry) {
  std::string others;
  for (const ObjectInfo& o : model.objects)
    if (o.kind == ObjectKind::fluid || o.has_bodies() || (o.kind == ObjectKind::soft_body && !model.suction_cups.empty()))
      others += fmt::format("{}'{}'", others.empty() ? "" : ", ", o.name);
  if (others.empty()) return;
  for (size_t k = 0; k < model.objects.size(); ++k) {
    const ObjectInfo& o = model.objects[k];
    if (o.kind == ObjectKind::collider && model.colliders[o.collider].removable())
      entry("objects", k).fail("until", fmt::format("a collider that is removed meets only cloth, soft bodies, grains and "
                                                    "shape-matched particles; this scene also has {} (fluids, rigid "
                                                    "bodies, rods or suction cups)", others));
  }
}

void add_object(const ObjectSpec& object, const SpecPlace& place, ObjectInfo& info, SceneBuildContext& ctx) {
  std::visit(
      [&](const auto& spec) {
        using T = std::decay_t<decltype(spec)>;
        if constexpr (std::is_same_v<T, ColliderSpec>) add_collider(spec, place, info, ctx);
        else if constexpr (std::is_same_v<T, ClothSpec>) add_cloth(spec, place, info, ctx);
        else if constexpr (std::is_same_v<T, SoftBodySpec>) add_soft_body(spec, place, info, ctx);
        else if constexpr (std::is_same_v<T, FluidSpec>) add_fluid(spec, place, info, ctx);
        else if constexpr (std::is_same_v<T, RodSpec>) add_rod(spec, place, info, ctx);
        else if constexpr (std::is_same_v<T, GranularSpec>) add_granular(spec, place, info, ctx);
        else if constexpr (std::is_same_v<T, ShapeMatchedSpec>) add_shape_matched(spec, place, info, ctx);
        else if constexpr (std::is_same_v<T, ContinuumSpec>) add_continuum(spec, place, info, ctx);
        else add_rigid_body(spec, place, info, ctx);
      },
      object);
}

}  // namespace

Scene assemble_scene(const SceneSpec& spec, const std::string& source, const std::string& file,
                     const std::filesystem::path& scene_directory) {
  auto entry = [&](const char* list, size_t k) { return SpecPlace(source, fmt::format("{}[{}]", list, k)); };
  const SpecPlace top(source, "");
  Scene scene;
  scene.file = file;
  scene.name = spec.name;
  if (scene.name.empty()) top.fail("name", "the scene name must not be empty");
  apply_settings(spec.settings, SpecPlace(source, "settings"), scene);

  std::vector<Vec3> initial_velocity;
  SceneBuildContext ctx{scene.model, initial_velocity, scene_directory, scene.duration};
  if (spec.objects.empty()) top.fail("objects", "a scene needs at least one object");
  for (size_t k = 0; k < spec.objects.size(); ++k) {
    const SpecPlace place = entry("objects", k);
    ObjectInfo info;
    info.name = object_name(spec.objects[k]);
    if (info.name.empty()) place.fail("name", "an object needs a name");
    if (scene.model.find_object(info.name) >= 0)
      place.fail("name", fmt::format("another object is already named '{}'; names must be unique", info.name));
    add_object(spec.objects[k], place, info, ctx);
    scene.model.objects.push_back(std::move(info));
  }
  check_removed_colliders(scene.model, entry);
  add_fluid_interfaces(spec.objects, scene.model, [&](Index k) { return entry("objects", k); });
  scene.model.color_constraints();
  finish_fluids(scene.model, [&](Index k) { return entry("objects", k); });
  for (size_t k = 0; k < spec.joints.size(); ++k) add_joint(spec.joints[k], entry("joints", k), scene.model);
  finish_joints(scene.model);
  add_colliders_as_bodies(scene.model);
  if (scene.model.settings.joint_solver == JointSolver::direct)
    scene.model.joint_forest = build_joint_forest(scene.model.rigid, scene.model.joints);

  for (size_t k = 0; k < spec.probes.size(); ++k)
    scene.probes.push_back(bind_probe(spec.probes[k], entry("probes", k), scene.model));

  scene.state = make_rest_state(scene.model);
  scene.state.velocity = initial_velocity;
  if (const std::string why = solver_refusal(scene.solver, scene.model); !why.empty())
    SpecPlace(source, "settings").fail("solver", why);
  scene.formulation = make_solver(scene.solver, scene.model);
  return scene;
}

}  // namespace moreau
