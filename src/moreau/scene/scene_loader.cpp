#include <fmt/format.h>

#include <filesystem>

#include "moreau/errors.hpp"
#include "moreau/scene/object_builders.hpp"
#include "moreau/scene/scene.hpp"

namespace moreau {

namespace {

void read_settings(const JsonObject& settings, Scene& scene) {
  SolverSettings& s = scene.model.settings;
  const std::string solver = settings.choice("solver", "xpbd", {"xpbd", "nmd", "xpbi", "fem"});
  if (solver != "xpbd")
    settings.fail("solver", fmt::format("the '{}' formulation is not available in this version of moreau; allowed: xpbd", solver));
  scene.solver = solver;
  s.dt = settings.number("dt", s.dt, Range::positive());
  s.substeps = settings.integer("substeps", s.substeps, 1, 100000);
  s.iterations = settings.integer("iterations", s.iterations, 1, 100000);
  scene.duration = settings.number("duration", scene.duration, Range::positive());
  s.gravity = settings.vec3("gravity", s.gravity);
  s.threads = settings.integer("threads", s.threads, 0, 1024);
  s.particle_contacts = settings.boolean("particle_contacts", s.particle_contacts);
  s.max_speed = settings.number("max_speed", s.max_speed, Range::positive());
  if (auto output = settings.optional_object("output")) {
    scene.output.every = output->integer("every", 1, 1);
    if (output->has("formats")) {
      const auto& formats = output->raw("formats");
      if (!formats.is_array()) output->fail("formats", "expected an array of format names; allowed: vtk");
      scene.output.write_vtk = false;
      for (const auto& f : formats) {
        if (!f.is_string() || f.get<std::string>() != "vtk")
          output->fail("formats", fmt::format("{} is not a known format; allowed: vtk", f.dump()));
        scene.output.write_vtk = true;
      }
    }
    output->finish();
  }
  settings.finish();
}

Index object_index(const JsonObject& probe, const Model& model, bool allow_all) {
  const std::string name = probe.string("object");
  if (allow_all && name == "*") return -1;
  const Index i = model.find_object(name);
  if (i < 0 || !model.objects[i].has_particles()) {
    std::string names;
    for (const auto& o : model.objects)
      if (o.has_particles()) names += (names.empty() ? "" : ", ") + o.name;
    probe.fail("object", fmt::format("no simulated object named '{}'; allowed: {}{}", name, names, allow_all ? ", *" : ""));
  }
  return i;
}

ProbeSpec read_probe(const JsonObject& j, const Model& model) {
  ProbeSpec p;
  p.name = j.string("name");
  const std::string type = j.choice("type", {"point", "energy", "center_of_mass", "extent", "momentum", "constraint_error"});
  if (type == "point") {
    p.type = ProbeType::point;
    p.object = object_index(j, model, false);
    const ObjectInfo& o = model.objects[p.object];
    if (j.has("vertex") == j.has("nearest")) j.fail("vertex", "give exactly one of \"vertex\" (index) or \"nearest\" (position, m)");
    if (j.has("vertex")) {
      p.particle = o.particle_begin + j.required_integer("vertex", 0, o.particle_count() - 1);
    } else {
      const Vec3 target = j.vec3("nearest");
      Real best = 1e300;
      for (Index q = o.particle_begin; q < o.particle_end; ++q) {
        const Real d = (model.particle_rest_position[q] - target).squaredNorm();
        if (d < best) best = d, p.particle = q;
      }
    }
    p.quantity = j.choice("quantity", "position", {"position", "displacement", "velocity"});
  } else if (type == "energy") {
    p.type = ProbeType::energy;
    p.object = object_index(j, model, true);
    p.quantity = j.choice("quantity", "total", {"kinetic", "potential", "elastic", "total"});
  } else if (type == "center_of_mass") {
    p.type = ProbeType::center_of_mass;
    p.object = object_index(j, model, true);
  } else if (type == "extent") {
    p.type = ProbeType::extent;
    p.object = object_index(j, model, true);
    const std::string axis = j.choice("axis", {"x", "y", "z"});
    p.axis = axis[0] - 'x';
    p.quantity = j.choice("quantity", {"min", "max"});
  } else if (type == "momentum") {
    p.type = ProbeType::momentum;
    p.object = object_index(j, model, true);
    p.quantity = j.choice("quantity", "linear", {"linear", "angular"});
    p.about = j.vec3("about", Vec3::Zero());
  } else {
    p.type = ProbeType::constraint_error;
    p.object = object_index(j, model, true);
    const std::string family = j.choice(
        "family", "all", {"all", "distance", "bending", "triangle_strain", "neo_hookean_volume", "tet_volume", "attachment"});
    static const std::vector<std::pair<std::string, ConstraintFamily>> kFamilies{
        {"all", ConstraintFamily::all},
        {"distance", ConstraintFamily::distance},
        {"bending", ConstraintFamily::bending},
        {"triangle_strain", ConstraintFamily::triangle_strain},
        {"neo_hookean_volume", ConstraintFamily::neo_hookean_volume},
        {"tet_volume", ConstraintFamily::tet_volume},
        {"attachment", ConstraintFamily::attachment}};
    for (const auto& [n, f] : kFamilies)
      if (n == family) p.family = f;
  }
  j.finish();
  return p;
}

}  // namespace

Scene load_scene(const std::string& path, const std::vector<std::string>& overrides) {
  nlohmann::json root = parse_json_file(path);
  for (const auto& o : overrides) apply_override(root, o, path);

  Scene scene;
  scene.file = path;
  const JsonObject top(root, "", path);
  scene.name = top.string("name");
  if (scene.name.empty()) top.fail("name", "the scene name must not be empty");
  top.allow("description");
  if (auto settings = top.optional_object("settings")) read_settings(*settings, scene);

  std::vector<Vec3> initial_velocity;
  SceneBuildContext ctx{scene.model, initial_velocity, std::filesystem::absolute(path).parent_path()};
  const auto objects = top.object_list("objects");
  if (objects.empty()) top.fail("objects", "a scene needs at least one object");
  for (const JsonObject& object : objects) {
    ObjectInfo info;
    info.name = object.string("name");
    if (scene.model.find_object(info.name) >= 0)
      object.fail("name", fmt::format("another object is already named '{}'; names must be unique", info.name));
    const std::string kind = object.choice("kind", {"collider", "cloth", "soft_body"});
    if (kind == "collider") build_collider(object, info, ctx);
    else if (kind == "cloth") build_cloth(object, info, ctx);
    else build_soft_body(object, info, ctx);
    object.finish();
    scene.model.objects.push_back(std::move(info));
  }
  scene.model.color_constraints();

  for (const JsonObject& probe : top.object_list("probes")) scene.probes.push_back(read_probe(probe, scene.model));
  top.finish();

  scene.state = make_rest_state(scene.model);
  scene.state.velocity = initial_velocity;
  return scene;
}

}  // namespace moreau
