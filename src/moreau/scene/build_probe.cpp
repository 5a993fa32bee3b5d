// "probes": what a run writes to probes.csv, bound to the model's objects, particles and joints.
#include <fmt/format.h>

#include <map>

#include "moreau/io/granular_probes.hpp"
#include "moreau/io/probes.hpp"
#include "moreau/scene/spec_builders.hpp"

namespace moreau {

namespace {

const std::vector<std::string> kProbeTypes{
    "point",    "energy",      "center_of_mass", "extent",           "momentum",    "constraint_error",
    "fluid_height", "density_error", "particle_count", "escaped",     "position",    "orientation",
    "velocity", "angular_velocity", "joint_error", "contact_count", "max_displacement",
    "penetration", "suction", "twist", "angle_of_repose", "mass_flow", "asleep", "runout",
    "temperature", "liquid_fraction"};

// The types whose only key besides name and type is "object": one simulated object or "*".
const std::map<std::string, ProbeType> kObjectOrEveryProbes{{"center_of_mass", ProbeType::center_of_mass},
                                                            {"contact_count", ProbeType::contact_count},
                                                            {"penetration", ProbeType::penetration},
                                                            {"max_displacement", ProbeType::max_displacement}};

// Every key a probe of this type may have (for the message on a misspelt key).
std::vector<std::string> probe_keys(const std::string& type) {
  std::vector<std::string> keys{"name", "type"};
  auto add = [&](std::initializer_list<const char*> more) { keys.insert(keys.end(), more.begin(), more.end()); };
  if (type == "joint_error") add({"joint"});
  else add({"object"});
  if (type == "point") add({"vertex", "nearest", "quantity"});
  if (type == "energy" || type == "density_error" || type == "temperature") add({"quantity"});
  if (type == "extent") add({"axis", "quantity"});
  if (type == "momentum") add({"quantity", "about"});
  if (type == "fluid_height") add({"at"});
  if (type == "escaped") add({"box"});
  if (type == "constraint_error") add({"family"});
  if (type == "angle_of_repose") add({"center", "bin", "box", "resting_speed"});
  if (type == "mass_flow") add({"point", "normal", "quantity"});
  if (type == "runout") add({"center", "direction", "fraction"});
  return keys;
}

enum class Accepts { any, fluids, solids, bodies, particles, rods, points, grains, piles };

Index object_index(const ProbeSpec& spec, const SpecPlace& probe, const Model& model, bool allow_all,
                   Accepts accepts = Accepts::any) {
  const std::string& name = spec.object;
  if (allow_all && name == "*") return -1;
  auto acceptable = [&](const ObjectInfo& o) {
    if (accepts == Accepts::fluids) return o.kind == ObjectKind::fluid;
    if (accepts == Accepts::solids) return o.has_particles();
    if (accepts == Accepts::bodies) return o.kind == ObjectKind::rigid_body;
    if (accepts == Accepts::particles) return o.has_particles() || o.kind == ObjectKind::fluid;
    if (accepts == Accepts::rods) return o.kind == ObjectKind::rod;
    if (accepts == Accepts::points) return o.has_particles() || o.kind == ObjectKind::rod;
    if (accepts == Accepts::grains) return o.kind == ObjectKind::granular;
    if (accepts == Accepts::piles) return o.kind == ObjectKind::granular || o.kind == ObjectKind::continuum;
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
                                     : accepts == Accepts::solids ? "particle (cloth, soft-body, granular or shape-matched) "
                                     : accepts == Accepts::bodies ? "rigid-body "
                                     : accepts == Accepts::particles ? "particle (cloth, soft-body, granular, shape-matched or fluid) "
                                     : accepts == Accepts::rods      ? "rod "
                                     : accepts == Accepts::points    ? "particle (cloth, soft-body, granular or shape-matched) or rod "
                                     : accepts == Accepts::grains    ? "granular "
                                     : accepts == Accepts::piles     ? "granular or continuum "
                                                                     : "simulated ",
                                     name, names));
  }
  return i;
}

// The probe's quantity, or `fallback` when not given.
std::string quantity(const ProbeSpec& spec, const SpecPlace& probe, const std::string& fallback,
                     const std::vector<std::string>& allowed) {
  return spec.quantity.empty() ? fallback : probe.choice("quantity", spec.quantity, allowed);
}

}  // namespace

ProbeSpec read_probe(const JsonObject& j) {
  ProbeSpec p;
  p.name = j.string("name");
  p.type = j.choice("type", kProbeTypes);
  j.expect_keys(probe_keys(p.type));
  if (p.type == "joint_error") p.joint = j.string("joint");
  else p.object = j.string("object");
  if (p.type == "point") {
    if (j.has("vertex")) p.vertex = read_integer(j, "vertex");
    p.nearest = read_optional_vector(j, "nearest");
  }
  if (p.type == "extent") {
    p.axis = j.string("axis");
    p.quantity = j.string("quantity");
  } else if (p.type == "point" || p.type == "energy" || p.type == "density_error" || p.type == "momentum" ||
             p.type == "mass_flow" || p.type == "temperature") {
    if (j.has("quantity")) p.quantity = j.string("quantity");
  }
  if (p.type == "momentum") p.about = read_vector(j, "about", p.about);
  if (p.type == "fluid_height") p.at = to_vector3(j.vec3("at"));
  if (p.type == "escaped" || (p.type == "angle_of_repose" && j.has("box"))) {
    const JsonObject box = j.object("box");
    p.box = FluidBlock{to_vector3(box.vec3("min")), to_vector3(box.vec3("max"))};
    box.finish();
  }
  if (p.type == "constraint_error" && j.has("family")) p.family = j.string("family");
  if (p.type == "angle_of_repose") {
    p.center = read_optional_vector(j, "center");
    p.bin = read_optional_number(j, "bin");
    p.resting_speed = read_optional_number(j, "resting_speed");
  }
  if (p.type == "runout") {
    p.center = read_optional_vector(j, "center");
    p.direction = read_optional_vector(j, "direction");
    p.fraction = read_optional_number(j, "fraction");
  }
  if (p.type == "mass_flow") {
    p.point = read_optional_vector(j, "point");
    p.normal = read_optional_vector(j, "normal");
  }
  j.finish();
  return p;
}

Probe bind_probe(const ProbeSpec& spec, const SpecPlace& j, const Model& model) {
  Probe p;
  p.name = spec.name;
  if (p.name.empty()) j.fail("name", "a probe needs a name");
  const std::string& type = j.choice("type", spec.type, kProbeTypes);
  if (type == "point") {
    p.type = ProbeType::point;
    p.object = object_index(spec, j, model, false, Accepts::points);
    const ObjectInfo& o = model.objects[p.object];
    if (spec.vertex.has_value() == spec.nearest.has_value())
      j.fail("vertex", "give exactly one of \"vertex\" (index) or \"nearest\" (position, m)");
    if (o.kind == ObjectKind::rod) {
      // A rod's centreline point, 0 to its segment count.
      p.type = ProbeType::rod_point;
      p.rod = o.rod;
      const RodModel& rod = model.rods[o.rod];
      if (spec.vertex) {
        p.rod_point = j.integer("vertex", *spec.vertex, 0, rod.points() - 1);
      } else {
        p.rod_point = rod.nearest_rest_point(j.vector("nearest", *spec.nearest));
      }
    } else {
      // Only the particles there from the start: an emitter's grains are not there until released.
      const Index initial_end = model.initial_particle_end(p.object);
      if (initial_end == o.particle_begin)
        j.fail("object", fmt::format("'{}' has no particle at the start (its grains come from an emitter)", o.name));
      if (spec.vertex) {
        p.particle = o.particle_begin + j.integer("vertex", *spec.vertex, 0, initial_end - o.particle_begin - 1);
      } else {
        const Vec3 target = j.vector("nearest", *spec.nearest);
        Real best = 1e300;
        for (Index q = o.particle_begin; q < initial_end; ++q) {
          const Real d = (model.particle_rest_position[q] - target).squaredNorm();
          if (d < best) best = d, p.particle = q;
        }
      }
    }
    p.quantity = quantity(spec, j, "position", {"position", "displacement", "velocity"});
  } else if (type == "energy") {
    p.type = ProbeType::energy;
    p.object = object_index(spec, j, model, true);
    p.quantity = quantity(spec, j, "total", {"kinetic", "potential", "elastic", "total"});
  } else if (const auto plain = kObjectOrEveryProbes.find(type); plain != kObjectOrEveryProbes.end()) {
    p.type = plain->second;
    p.object = object_index(spec, j, model, true);
  } else if (type == "extent") {
    p.type = ProbeType::extent;
    p.object = object_index(spec, j, model, true, Accepts::particles);  // particles only
    if (spec.axis.empty()) j.fail("axis", "missing required key");
    p.axis = j.choice("axis", spec.axis, {"x", "y", "z"})[0] - 'x';
    if (spec.quantity.empty()) j.fail("quantity", "missing required key");
    p.quantity = quantity(spec, j, "", {"min", "max"});
  } else if (type == "momentum") {
    p.type = ProbeType::momentum;
    p.object = object_index(spec, j, model, true);
    p.quantity = quantity(spec, j, "linear", {"linear", "angular"});
    p.about = j.vector("about", spec.about);
  } else if (type == "fluid_height") {
    p.type = ProbeType::fluid_height;
    p.object = object_index(spec, j, model, true, Accepts::fluids);
    p.at = j.required_vector("at", spec.at);
  } else if (type == "density_error") {
    p.type = ProbeType::density_error;
    p.object = object_index(spec, j, model, true, Accepts::fluids);
    p.quantity = quantity(spec, j, "mean", {"mean", "max"});
  } else if (type == "temperature" || type == "liquid_fraction") {
    p.type = type == "temperature" ? ProbeType::temperature : ProbeType::liquid_fraction;
    p.object = object_index(spec, j, model, true, Accepts::fluids);
    if (!model.fluid.thermal)
      j.fail("type", fmt::format("a \"{}\" probe reads the fluids' heat, and no fluid of the scene has a \"thermal\" "
                                 "entry",
                                 type));
    if (type == "temperature") p.quantity = quantity(spec, j, "mean", {"mean", "min", "max"});
  } else if (type == "asleep") {
    p.type = ProbeType::asleep;
    p.object = object_index(spec, j, model, true, Accepts::grains);
  } else if (type == "particle_count") {
    p.type = ProbeType::particle_count;
    p.object = object_index(spec, j, model, true, Accepts::particles);  // particles only
  } else if (type == "position" || type == "orientation" || type == "velocity" || type == "angular_velocity") {
    p.type = type == "position"      ? ProbeType::body_position
             : type == "orientation" ? ProbeType::body_orientation
             : type == "velocity"    ? ProbeType::body_velocity
                                     : ProbeType::body_angular_velocity;
    p.object = object_index(spec, j, model, false, Accepts::bodies);
  } else if (type == "joint_error") {
    p.type = ProbeType::joint_error;
    if (spec.joint != "*") {
      for (Index k = 0; k < static_cast<Index>(model.joints.size()); ++k)
        if (model.joints[k].name == spec.joint) p.joint = k;
      if (p.joint < 0) j.fail("joint", fmt::format("no joint is named '{}'; give a joint's name or \"*\"", spec.joint));
    }
  } else if (type == "suction") {
    p.type = ProbeType::suction;
    const Index object = model.find_object(spec.object);
    for (Index k = 0; k < static_cast<Index>(model.suction_cups.size()); ++k)
      if (model.suction_cups[k].object == object) p.cup = k;
    if (p.cup < 0) {
      std::string names;
      for (const SuctionCup& c : model.suction_cups) names += (names.empty() ? "" : ", ") + model.objects[c.object].name;
      j.fail("object", fmt::format("no soft body named '{}' has \"suction\"; allowed: {}", spec.object,
                                   names.empty() ? "none (the scene has no suction cup)" : names));
    }
    p.object = object;
  } else if (type == "twist") {
    p.type = ProbeType::rod_twist;
    p.object = object_index(spec, j, model, false, Accepts::rods);
    p.rod = model.objects[p.object].rod;
  } else if (type == "angle_of_repose") {
    p.type = ProbeType::angle_of_repose;
    p.object = object_index(spec, j, model, false, Accepts::piles);
    if (spec.center) p.pile_axis = j.vector("center", *spec.center);
    Real largest_radius = 0;
    const ObjectInfo& o = model.objects[p.object];
    for (Index q = o.particle_begin; q < o.particle_end; ++q) largest_radius = std::max(largest_radius, model.particle_radius[q]);
    p.ring_width = spec.bin ? j.number("bin", *spec.bin, Range::positive()) : 2 * largest_radius;
    if (spec.box) p.pile_region = std::make_pair(j.vector("box.min", spec.box->min), j.vector("box.max", spec.box->max));
    if (spec.resting_speed) p.resting_speed = j.number("resting_speed", *spec.resting_speed, Range::positive());
  } else if (type == "runout") {
    p.type = ProbeType::runout;
    p.object = object_index(spec, j, model, false, Accepts::particles);
    if (spec.center) p.pile_axis = j.vector("center", *spec.center);
    if (spec.direction) {
      if (!spec.center) j.fail("direction", "a runout along a direction is measured from a point: give \"center\" (m) too");
      const Vec3 d = j.vector("direction", *spec.direction);
      const Vec3 up = up_direction(model);
      const Vec3 horizontal = d - d.dot(up) * up;
      if (!(horizontal.norm() > 1e-9 * d.norm()) || !(d.norm() > 0))
        j.fail("direction", "the direction must have a horizontal part (across gravity)");
      p.runout_direction = horizontal.normalized();
    }
    if (spec.fraction) p.runout_fraction = j.number("fraction", *spec.fraction, Range{0, 1, true, false});
  } else if (type == "mass_flow") {
    p.type = ProbeType::mass_flow;
    p.object = object_index(spec, j, model, true, Accepts::particles);  // particles only
    p.plane_point = j.required_vector("point", spec.point);
    if (!spec.normal) j.fail("normal", "missing required key: the plane's normal, the direction counted positive");
    const Vec3 n = j.vector("normal", *spec.normal);
    if (!(n.norm() > 0)) j.fail("normal", "the normal must not be zero");
    p.plane_normal = n.normalized();
    p.quantity = quantity(spec, j, "rate", {"rate", "beyond"});
  } else if (type == "escaped") {
    p.type = ProbeType::escaped;
    p.object = object_index(spec, j, model, true, Accepts::particles);  // particles only
    if (!spec.box) j.fail("box", "missing required key");
    p.box_min = j.vector("box.min", spec.box->min);
    p.box_max = j.vector("box.max", spec.box->max);
  } else {
    p.type = ProbeType::constraint_error;
    p.object = object_index(spec, j, model, true, Accepts::solids);
    const auto names = constraint_error_names();
    p.family = j.choice("family", spec.family, std::vector<std::string>(names.begin(), names.end()));
  }
  return p;
}

}  // namespace moreau
