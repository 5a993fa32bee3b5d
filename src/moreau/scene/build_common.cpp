// What the object kinds share: contact materials, pins, particles, mesh files and rotations.
#include <fmt/format.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <limits>

#include "moreau/errors.hpp"
#include "moreau/geometry/mesh_readers.hpp"
#include "moreau/scene/spec_builders.hpp"

namespace moreau {

Vector3 read_vector(const JsonObject& object, const std::string& key, const Vector3& fallback) {
  return object.has(key) ? to_vector3(object.vec3(key)) : fallback;
}

std::optional<Vector3> read_optional_vector(const JsonObject& object, const std::string& key) {
  if (!object.has(key)) return std::nullopt;
  return to_vector3(object.vec3(key));
}

std::optional<double> read_optional_number(const JsonObject& object, const std::string& key) {
  if (!object.has(key)) return std::nullopt;
  return object.number(key);
}

FluidBlock read_block(const JsonObject& block) {
  FluidBlock b{to_vector3(block.vec3("min")), to_vector3(block.vec3("max"))};
  block.finish();
  return b;
}

std::optional<Vector2> read_optional_pair(const JsonObject& object, const std::string& key) {
  if (!object.has(key)) return std::nullopt;
  const Vec2 v = object.vec2(key, Range::any());
  return Vector2{v.x(), v.y()};
}

int read_integer(const JsonObject& object, const std::string& key) {
  return object.required_integer(key, std::numeric_limits<int>::min(), std::numeric_limits<int>::max());
}

ContactMaterial read_contact_material(const JsonObject& object) {
  ContactMaterial m;
  if (object.has("friction")) {
    if (object.raw("friction").is_number()) {
      m.static_friction = m.dynamic_friction = object.number("friction");
    } else {
      const JsonObject friction = object.object("friction");
      m.static_friction = friction.number("static");
      m.dynamic_friction = friction.number("dynamic", m.static_friction);
      friction.finish();
    }
  }
  m.restitution = object.number("restitution", m.restitution);
  m.adhesion = object.number("adhesion", m.adhesion);
  return m;
}

void set_fluid_coupling(bool coupling, double friction, const SpecPlace& place, ObjectInfo& info) {
  info.fluid_coupling = coupling;
  info.fluid_friction = place.number("fluid_friction", friction, Range::closed(0, 1));
  if (info.fluid_friction > 0 && !info.fluid_coupling)
    place.fail("fluid_friction", "an object with \"fluid_coupling\": false has no surface samples to carry the "
                                 "fluid's wall friction; remove \"fluid_friction\" or couple the object");
}

void set_contact_material(const ContactMaterial& contact, const SpecPlace& place, ObjectInfo& info) {
  // One coefficient (static = dynamic) is the scene file's "friction": mu.
  if (contact.static_friction == contact.dynamic_friction) {
    place.number("friction", contact.static_friction, Range::non_negative());
  } else {
    place.number("friction.static", contact.static_friction, Range::non_negative());
    place.number("friction.dynamic", contact.dynamic_friction, Range::non_negative());
  }
  info.static_friction = contact.static_friction;
  info.dynamic_friction = contact.dynamic_friction;
  info.restitution = place.number("restitution", contact.restitution, Range::closed(0, 1));
  info.adhesion = place.number("adhesion", contact.adhesion, Range::non_negative());
}

std::vector<PinSpec> read_pins(const JsonObject& object) {
  std::vector<PinSpec> pins;
  for (const JsonObject& pin : object.object_list("pin")) {
    PinSpec spec;
    spec.compliance = pin.number("compliance", 0.0);
    spec.damping = pin.number("damping", 0.0);
    if (pin.has("box")) {
      const JsonObject box = pin.object("box");
      spec.region = PinBox{to_vector3(box.vec3("min")), to_vector3(box.vec3("max"))};
      box.finish();
    } else if (pin.has("sphere")) {
      const JsonObject sphere = pin.object("sphere");
      PinSphere s;
      s.center = to_vector3(sphere.vec3("center"));
      s.radius = sphere.number("radius");
      spec.region = s;
      sphere.finish();
    } else if (pin.has("vertices")) {
      spec.region = pin.integer_list("vertices", 0);
    } else {
      pin.fail("box", "a pin needs a region: \"box\", \"sphere\" or \"vertices\"");
    }
    pin.finish();
    pins.push_back(std::move(spec));
  }
  return pins;
}

MeshFile read_mesh_file(const JsonObject& mesh) {
  MeshFile file;
  file.file = mesh.string("file");
  file.scale = mesh.number("scale", file.scale);
  file.translate = read_vector(mesh, "translate", file.translate);
  return file;
}

Mat3 rotation_from_degrees(const Vec3& degrees) {
  const Vec3 r = degrees * kPi / 180.0;
  return (Eigen::AngleAxisd(r.z(), Vec3::UnitZ()) * Eigen::AngleAxisd(r.y(), Vec3::UnitY()) *
          Eigen::AngleAxisd(r.x(), Vec3::UnitX()))
      .toRotationMatrix();
}

void add_particles(SceneBuildContext& ctx, ObjectInfo& info, const std::vector<Vec3>& positions,
                   const std::vector<Real>& masses, Real radius, Real collider_gap, const Vec3& velocity) {
  Model& m = ctx.model;
  info.particle_begin = m.particle_count();
  const Index object_index = static_cast<Index>(m.objects.size());
  for (size_t i = 0; i < positions.size(); ++i) {
    m.particle_rest_position.push_back(positions[i]);
    m.particle_mass.push_back(masses[i]);
    m.particle_inv_mass.push_back(masses[i] > 0 ? 1.0 / masses[i] : 0.0);
    m.particle_inv_inertia.push_back(0);
    m.particle_radius.push_back(radius);
    m.particle_collider_gap.push_back(collider_gap);
    m.particle_object.push_back(object_index);
    ctx.initial_velocity.push_back(velocity);
  }
  info.particle_end = m.particle_count();
}

namespace {

// The object's particles inside one pin region.
std::vector<Index> pinned_particles(const PinSpec& pin, const SpecPlace& place, const ObjectInfo& info, const Model& m) {
  std::vector<Index> selected;
  std::string field;
  if (const auto* box = std::get_if<PinBox>(&pin.region)) {
    field = "box";
    const Vec3 lo = place.vector("box.min", box->min), hi = place.vector("box.max", box->max);
    for (Index p = info.particle_begin; p < info.particle_end; ++p) {
      const Vec3& x = m.particle_rest_position[p];
      if ((x.array() >= lo.array()).all() && (x.array() <= hi.array()).all()) selected.push_back(p);
    }
  } else if (const auto* sphere = std::get_if<PinSphere>(&pin.region)) {
    field = "sphere";
    const Vec3 c = place.vector("sphere.center", sphere->center);
    const Real r = place.number("sphere.radius", sphere->radius, Range::positive());
    for (Index p = info.particle_begin; p < info.particle_end; ++p)
      if ((m.particle_rest_position[p] - c).norm() <= r) selected.push_back(p);
  } else {
    field = "vertices";
    for (int v : std::get<PinVertices>(pin.region)) {
      if (v < 0 || v >= info.particle_count())
        place.fail("vertices", fmt::format("vertex {} does not exist; the object has {} vertices", v, info.particle_count()));
      selected.push_back(info.particle_begin + v);
    }
  }
  if (selected.empty()) place.fail(field, "this pin region contains no vertex of the object; check its coordinates (m)");
  return selected;
}

}  // namespace

void add_pins(const std::vector<PinSpec>& pins, const SpecPlace& place, const ObjectInfo& info, SceneBuildContext& ctx) {
  Model& m = ctx.model;
  AttachmentConstraints& attachments = m.family<AttachmentConstraints>();
  const Index object_index = static_cast<Index>(m.objects.size());
  for (size_t k = 0; k < pins.size(); ++k) {
    const PinSpec& pin = pins[k];
    const SpecPlace at = place.at(fmt::format("pin[{}]", k));
    const Real compliance = at.number("compliance", pin.compliance, Range::non_negative());
    const Real damping = at.number("damping", pin.damping, Range::non_negative());
    for (Index p : pinned_particles(pin, at, info, m)) {
      // A particle already pinned rigidly, or attached by an earlier region, keeps that pin: two
      // attachments on one particle would also race in the attachments' parallel loop.
      if (m.particle_inv_mass[p] == 0 ||
          std::find(attachments.particle.begin(), attachments.particle.end(), p) != attachments.particle.end())
        continue;
      if (compliance == 0) {
        m.particle_inv_mass[p] = 0;
        ctx.initial_velocity[p] = Vec3::Zero();
      } else {
        attachments.add(p, m.particle_rest_position[p], compliance, damping, object_index);
      }
    }
  }
}

std::string resolve_path(const SceneBuildContext& ctx, const std::string& path) {
  const std::filesystem::path p(path);
  const std::string resolved = p.is_absolute() ? p.string() : (ctx.scene_directory / p).string();
  std::error_code ec;
  if (std::filesystem::is_directory(resolved, ec))
    throw InputError(fmt::format("{}: is a directory; give the path of a mesh file", resolved));
  return resolved;
}

ClosedSurface read_closed_surface(const SceneBuildContext& ctx, const SpecPlace& place, const std::string& field,
                                  const std::string& file) {
  const std::string path = resolve_path(ctx, file);
  ClosedSurface surface;
  try {
    surface.mesh = read_obj_triangles(path);
  } catch (const std::exception& e) {
    place.fail(field, e.what());
  }
  if (surface.mesh.vertices.empty()) place.fail(field, fmt::format("'{}' has no vertices", path));
  surface.lo = surface.hi = surface.mesh.vertices.front();
  for (const Vec3& v : surface.mesh.vertices) surface.lo = surface.lo.cwiseMin(v), surface.hi = surface.hi.cwiseMax(v);
  return surface;
}

void place_vertices(const MeshFile& file, const SpecPlace& place, std::vector<Vec3>& vertices) {
  const Real scale = place.number("scale", file.scale, Range::positive());
  const Vec3 translate = place.vector("translate", file.translate);
  for (auto& v : vertices) v = scale * v + translate;
}

}  // namespace moreau
