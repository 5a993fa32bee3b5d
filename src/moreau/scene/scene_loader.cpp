#include <fmt/format.h>
#include <fmt/ranges.h>

#include <filesystem>

#include "moreau/errors.hpp"
#include "moreau/scene/fem_scene.hpp"
#include "moreau/scene/object_builders.hpp"
#include "moreau/scene/scene.hpp"
#include "moreau/solvers/solver_registry.hpp"

namespace moreau {

namespace {

void read_output_settings(const JsonObject& settings, Scene& scene) {
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
}

void read_settings(const JsonObject& settings, Scene& scene) {
  SolverSettings& s = scene.model.settings;
  // The scene format names every formulation; those not registered (solver_registry.hpp) are
  // refused with the list of the ones that are.
  std::vector<std::string> available = registered_solver_names();
  available.push_back("fem");
  const std::string solver = settings.choice("solver", "xpbd", {"xpbd", "nmd", "xpbi", "fem"});
  if (std::find(available.begin(), available.end(), solver) == available.end())
    settings.fail("solver", fmt::format("the '{}' formulation is not available in this version of moreau; allowed: {}",
                                        solver, fmt::join(available, ", ")));
  scene.solver = solver;
  if (solver == "fem") {
    scene.fem = std::make_unique<FemProblem>();
    allow_fem_settings(settings);
  }
  Real& dt = solver == "fem" ? scene.fem->dt : s.dt;
  dt = settings.number("dt", dt, Range::positive());
  scene.duration = settings.number("duration", scene.duration, Range::positive());
  s.gravity = settings.vec3("gravity", s.gravity);
  s.threads = settings.integer("threads", s.threads, 0, 1024);
  if (solver == "fem") {
    // The FEM engine reads its own keys (allow_fem_settings); the XPBD ones below would be
    // accepted and ignored, so they are not offered.
    read_output_settings(settings, scene);
    settings.finish();
    return;
  }
  s.substeps = settings.integer("substeps", s.substeps, 1, 100000);
  s.iterations = settings.integer("iterations", s.iterations, 1, 100000);
  s.particle_contacts = settings.boolean("particle_contacts", s.particle_contacts);
  s.max_speed = settings.number("max_speed", s.max_speed, Range::positive());
  s.joint_solver = settings.choice("joint_solver", "direct", {"direct", "gauss_seidel"}) == "direct"
                       ? JointSolver::direct
                       : JointSolver::gauss_seidel;
  if (auto fluid = settings.optional_object("fluid")) {
    FluidModel& fm = scene.model.fluid;
    fm.neighbor_skin_fraction = fluid->number("neighbor_skin", fm.neighbor_skin_fraction, Range::closed(0, 1));
    fm.tensile_k = fluid->number("tensile_k", fm.tensile_k, Range::closed(0, 10));
    fm.cfl_limit = fluid->number("cfl_limit", fm.cfl_limit, Range::positive());
    fluid->finish();
  }
  read_output_settings(settings, scene);
  settings.finish();
}

enum class Accepts { any, fluids, solids, bodies, particles };

Index object_index(const JsonObject& probe, const Model& model, bool allow_all, Accepts accepts = Accepts::any) {
  const std::string name = probe.string("object");
  if (allow_all && name == "*") return -1;
  auto acceptable = [&](const ObjectInfo& o) {
    if (accepts == Accepts::fluids) return o.kind == ObjectKind::fluid;
    if (accepts == Accepts::solids) return o.has_particles();
    if (accepts == Accepts::bodies) return o.kind == ObjectKind::rigid_body;
    if (accepts == Accepts::particles) return o.has_particles() || o.kind == ObjectKind::fluid;
    return o.is_simulated();
  };
  const Index i = model.find_object(name);
  if (i < 0 || !acceptable(model.objects[i])) {
    std::string names;
    for (const auto& o : model.objects)
      if (acceptable(o)) names += (names.empty() ? "" : ", ") + o.name;
    if (names.empty()) names = allow_all ? "\"*\" (the scene has no such object)" : "none (the scene has no such object)";
    else if (allow_all) names += ", *";
    probe.fail("object", fmt::format("no {}object named '{}'; allowed: {}",
                                     accepts == Accepts::fluids   ? "fluid "
                                     : accepts == Accepts::solids ? "cloth or soft-body "
                                     : accepts == Accepts::bodies ? "rigid-body "
                                     : accepts == Accepts::particles ? "cloth, soft-body or fluid "
                                                                     : "simulated ",
                                     name, names));
  }
  return i;
}

// Every key a probe of this type may have (for the message on a misspelt key).
std::vector<std::string> probe_keys(const std::string& type) {
  std::vector<std::string> keys{"name", "type"};
  auto add = [&](std::initializer_list<const char*> more) { keys.insert(keys.end(), more.begin(), more.end()); };
  if (type == "joint_error") add({"joint"});
  else add({"object"});
  if (type == "point") add({"vertex", "nearest", "quantity"});
  if (type == "energy" || type == "density_error") add({"quantity"});
  if (type == "extent") add({"axis", "quantity"});
  if (type == "momentum") add({"quantity", "about"});
  if (type == "fluid_height") add({"at"});
  if (type == "escaped") add({"box"});
  if (type == "constraint_error") add({"family"});
  return keys;
}

ProbeSpec read_probe(const JsonObject& j, const Model& model) {
  ProbeSpec p;
  p.name = j.string("name");
  const std::string type = j.choice("type", {"point", "energy", "center_of_mass", "extent", "momentum", "constraint_error",
                                             "fluid_height", "density_error", "particle_count", "escaped",
                                             "position", "orientation", "velocity", "angular_velocity", "joint_error",
                                             "contact_count", "max_displacement"});
  j.expect_keys(probe_keys(type));
  if (type == "point") {
    p.type = ProbeType::point;
    p.object = object_index(j, model, false, Accepts::solids);
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
    p.object = object_index(j, model, true, Accepts::particles);  // particles only
    const std::string axis = j.choice("axis", {"x", "y", "z"});
    p.axis = axis[0] - 'x';
    p.quantity = j.choice("quantity", {"min", "max"});
  } else if (type == "momentum") {
    p.type = ProbeType::momentum;
    p.object = object_index(j, model, true);
    p.quantity = j.choice("quantity", "linear", {"linear", "angular"});
    p.about = j.vec3("about", Vec3::Zero());
  } else if (type == "fluid_height") {
    p.type = ProbeType::fluid_height;
    p.object = object_index(j, model, true, Accepts::fluids);
    p.at = j.vec3("at");
  } else if (type == "density_error") {
    p.type = ProbeType::density_error;
    p.object = object_index(j, model, true, Accepts::fluids);
    p.quantity = j.choice("quantity", "mean", {"mean", "max"});
  } else if (type == "particle_count") {
    p.type = ProbeType::particle_count;
    p.object = object_index(j, model, true, Accepts::particles);  // particles only
  } else if (type == "position" || type == "orientation" || type == "velocity" || type == "angular_velocity") {
    p.type = type == "position"      ? ProbeType::body_position
             : type == "orientation" ? ProbeType::body_orientation
             : type == "velocity"    ? ProbeType::body_velocity
                                     : ProbeType::body_angular_velocity;
    p.object = object_index(j, model, false, Accepts::bodies);
  } else if (type == "joint_error") {
    p.type = ProbeType::joint_error;
    const std::string name = j.string("joint");
    if (name != "*") {
      for (Index k = 0; k < static_cast<Index>(model.joints.size()); ++k)
        if (model.joints[k].name == name) p.joint = k;
      if (p.joint < 0) j.fail("joint", fmt::format("no joint is named '{}'; give a joint's name or \"*\"", name));
    }
  } else if (type == "contact_count") {
    p.type = ProbeType::contact_count;
    p.object = object_index(j, model, true);
  } else if (type == "max_displacement") {
    p.type = ProbeType::max_displacement;
    p.object = object_index(j, model, true);
  } else if (type == "escaped") {
    p.type = ProbeType::escaped;
    p.object = object_index(j, model, true, Accepts::particles);  // particles only
    const JsonObject box = j.object("box");
    p.box_min = box.vec3("min");
    p.box_max = box.vec3("max");
    box.finish();
  } else {
    p.type = ProbeType::constraint_error;
    p.object = object_index(j, model, true, Accepts::solids);
    const auto names = constraint_error_names();
    p.family = j.choice("family", "all", std::vector<std::string>(names.begin(), names.end()));
  }
  j.finish();
  return p;
}

// Validates and builds the scene in `root` (read from `path`) after applying the overrides.
Scene build_scene(nlohmann::json root, const std::string& path, const std::vector<std::string>& overrides) {
  for (const auto& o : overrides) apply_override(root, o, path);

  Scene scene;
  scene.file = path;
  const JsonObject top(root, "", path);
  scene.name = top.string("name");
  if (scene.name.empty()) top.fail("name", "the scene name must not be empty");
  top.allow("description");
  if (auto settings = top.optional_object("settings")) read_settings(*settings, scene);

  if (scene.fem) {
    build_fem_scene(top, *scene.fem, scene.model.settings.gravity, scene.model.settings.threads);
    top.finish();
    return scene;
  }

  std::vector<Vec3> initial_velocity;
  SceneBuildContext ctx{scene.model, initial_velocity, std::filesystem::absolute(path).parent_path(), scene.duration};
  const auto objects = top.object_list("objects");
  if (objects.empty()) top.fail("objects", "a scene needs at least one object");
  for (const JsonObject& object : objects) {
    ObjectInfo info;
    info.name = object.string("name");
    if (scene.model.find_object(info.name) >= 0)
      object.fail("name", fmt::format("another object is already named '{}'; names must be unique", info.name));
    const std::string kind = object.choice("kind", {"collider", "cloth", "soft_body", "fluid", "rigid_body"});
    if (kind == "collider") build_collider(object, info, ctx);
    else if (kind == "rigid_body") build_rigid_body(object, info, ctx);
    else if (kind == "cloth") build_cloth(object, info, ctx);
    else if (kind == "fluid") build_fluid(object, info, ctx);
    else build_soft_body(object, info, ctx);
    object.finish();
    scene.model.objects.push_back(std::move(info));
  }
  scene.model.color_constraints();
  finish_fluids(scene.model);
  if (top.has("joints")) build_joints(top.object_list("joints"), scene.model);
  add_colliders_as_bodies(scene.model);
  if (scene.model.settings.joint_solver == JointSolver::direct)
    scene.model.joint_forest = build_joint_forest(scene.model.rigid, scene.model.joints);

  for (const JsonObject& probe : top.object_list("probes")) scene.probes.push_back(read_probe(probe, scene.model));
  top.finish();

  scene.state = make_rest_state(scene.model);
  scene.state.velocity = initial_velocity;
  scene.formulation = make_solver(scene.solver, scene.model);
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
