#include <fmt/format.h>

#include <Eigen/Geometry>
#include <algorithm>

#include "moreau/errors.hpp"
#include "moreau/scene/object_builders.hpp"

namespace moreau {

Mat3 rotation_from_degrees(const Vec3& degrees) {
  const Vec3 r = degrees * kPi / 180.0;
  return (Eigen::AngleAxisd(r.z(), Vec3::UnitZ()) * Eigen::AngleAxisd(r.y(), Vec3::UnitY()) *
          Eigen::AngleAxisd(r.x(), Vec3::UnitX()))
      .toRotationMatrix();
}

void read_contact_material(const JsonObject& object, Real& mu_static, Real& mu_dynamic, Real& restitution) {
  if (object.has("friction")) {
    const auto& f = object.raw("friction");
    if (f.is_number()) {
      mu_static = mu_dynamic = object.number("friction", Range::non_negative());
    } else {
      const JsonObject friction = object.object("friction");
      mu_static = friction.number("static", Range::non_negative());
      mu_dynamic = friction.number("dynamic", mu_static, Range::non_negative());
      friction.finish();
    }
  }
  restitution = object.number("restitution", restitution, Range::closed(0, 1));
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
    m.particle_radius.push_back(radius);
    m.particle_collider_gap.push_back(collider_gap);
    m.particle_object.push_back(object_index);
    ctx.initial_velocity.push_back(velocity);
  }
  info.particle_end = m.particle_count();
}

void read_pins(const JsonObject& object, const ObjectInfo& info, SceneBuildContext& ctx) {
  Model& m = ctx.model;
  AttachmentConstraints& attachments = m.family<AttachmentConstraints>();
  const Index object_index = static_cast<Index>(m.objects.size());
  for (const JsonObject& pin : object.object_list("pin")) {
    const Real compliance = pin.number("compliance", 0.0, Range::non_negative());
    const Real damping = pin.number("damping", 0.0, Range::non_negative());
    std::vector<Index> selected;
    if (pin.has("box")) {
      const JsonObject box = pin.object("box");
      const Vec3 lo = box.vec3("min"), hi = box.vec3("max");
      box.finish();
      for (Index p = info.particle_begin; p < info.particle_end; ++p) {
        const Vec3& x = m.particle_rest_position[p];
        if ((x.array() >= lo.array()).all() && (x.array() <= hi.array()).all()) selected.push_back(p);
      }
    } else if (pin.has("sphere")) {
      const JsonObject sphere = pin.object("sphere");
      const Vec3 c = sphere.vec3("center");
      const Real r = sphere.number("radius", Range::positive());
      sphere.finish();
      for (Index p = info.particle_begin; p < info.particle_end; ++p)
        if ((m.particle_rest_position[p] - c).norm() <= r) selected.push_back(p);
    } else if (pin.has("vertices")) {
      for (int v : pin.integer_list("vertices", 0)) {
        if (v >= info.particle_count())
          pin.fail("vertices", fmt::format("vertex {} does not exist; the object has {} vertices", v, info.particle_count()));
        selected.push_back(info.particle_begin + v);
      }
    } else {
      pin.fail("box", "a pin needs a region: \"box\", \"sphere\" or \"vertices\"");
    }
    pin.finish();
    if (selected.empty())
      pin.fail(pin.has("box") ? "box" : pin.has("sphere") ? "sphere" : "vertices",
               "this pin region contains no vertex of the object; check its coordinates (m)");
    for (Index p : selected) {
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

}  // namespace moreau
