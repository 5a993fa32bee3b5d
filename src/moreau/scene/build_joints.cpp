// The scene's "joints" list (see joints.hpp for the constraints and docs/scene-format.md).
#include <fmt/format.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "moreau/scene/object_builders.hpp"

namespace moreau {

namespace {

constexpr Real kDegree = kPi / 180;

// One end: "world", a rigid body's name, or {"object": cloth/soft body, "vertex": i | "nearest": p}.
JointEnd read_end(const JsonObject& joint, const nlohmann::json& value, int slot, const Model& model) {
  JointEnd end;
  const std::string where = fmt::format("bodies[{}]", slot);
  if (value.is_string()) {
    const std::string name = value.get<std::string>();
    if (name == "world") return end;
    const Index o = model.find_object(name);
    if (o < 0 || model.objects[o].kind != ObjectKind::rigid_body)
      joint.fail("bodies", fmt::format("{} is '{}', which is not a rigid body of this scene; give \"world\", a rigid "
                                       "body's name or {{\"object\": <cloth or soft body>, \"vertex\": i}}",
                                       where, name));
    end.kind = BodyEndKind::body;
    end.index = model.objects[o].body;
    return end;
  }
  if (!value.is_object()) joint.fail("bodies", fmt::format("{} must be a name or an object", where));
  const JsonObject ref(value, joint.path_of("bodies") + fmt::format("[{}]", slot), joint.file());
  const std::string name = ref.string("object");
  const Index o = model.find_object(name);
  if (o < 0 || !model.objects[o].has_particles())
    ref.fail("object", fmt::format("'{}' is not a cloth or soft body of this scene", name));
  const ObjectInfo& info = model.objects[o];
  end.kind = BodyEndKind::particle;
  if (ref.has("vertex") == ref.has("nearest")) ref.fail("vertex", "give exactly one of \"vertex\" or \"nearest\"");
  if (ref.has("vertex")) {
    const int v = ref.integer("vertex", 0, 0, info.particle_count() - 1);
    end.index = info.particle_begin + v;
  } else {
    const Vec3 p = ref.vec3("nearest");
    Index best = info.particle_begin;
    for (Index i = info.particle_begin; i < info.particle_end; ++i)
      if ((model.particle_rest_position[i] - p).squaredNorm() < (model.particle_rest_position[best] - p).squaredNorm())
        best = i;
    end.index = best;
  }
  ref.finish();
  return end;
}

// Frame whose x axis is `axis` (unit), its y axis a fixed perpendicular.
Quat frame_from_axis(const Vec3& axis) {
  const Vec3 helper = std::abs(axis.y()) < 0.9 ? Vec3::UnitY() : Vec3::UnitZ();
  const Vec3 z = axis.cross(helper).normalized();
  const Vec3 y = z.cross(axis);
  Mat3 R;
  R << axis, y, z;
  return Quat(R).normalized();
}

// Centre, orientation and the world anchor of an end at scene time.
void attach(JointEnd& end, const Vec3& anchor, const Quat& frame, const Model& model) {
  switch (end.kind) {
    case BodyEndKind::world:
      end.anchor = anchor;
      end.frame = frame;
      break;
    case BodyEndKind::body: {
      const Quat& q = model.rigid.initial_orientation[end.index];
      end.anchor = q.conjugate() * (anchor - model.rigid.initial_position[end.index]);
      end.frame = (q.conjugate() * frame).normalized();
      break;
    }
    case BodyEndKind::particle:
      end.anchor = Vec3::Zero();
      break;
  }
}

Vec3 end_world_point(const JointEnd& end, const Model& model) {
  if (end.kind == BodyEndKind::body)
    return model.rigid.initial_position[end.index] + model.rigid.initial_orientation[end.index] * end.anchor;
  if (end.kind == BodyEndKind::particle) return model.particle_rest_position[end.index];
  return end.anchor;
}

Vec2 read_degrees_range(const JsonObject& j, const std::string& key) {
  const Vec2 r = j.vec2(key, Range::closed(-180, 180));
  if (r.x() > r.y()) j.fail(key, "the lower limit must not exceed the upper one");
  return r * kDegree;
}

void read_drive(const JsonObject& j, Joint& joint) {
  const auto drive = j.optional_object("drive");
  if (!drive) return;
  const bool angular = joint.type == JointType::hinge;
  if (!angular && joint.type != JointType::prismatic)
    j.fail("drive", "only hinge and prismatic joints have drives");
  const std::string position_key = angular ? "target_angle_deg" : "target_position";
  if (drive->has(position_key) == drive->has("target_velocity"))
    drive->fail(position_key, fmt::format("give exactly one of \"{}\" or \"target_velocity\" ({})", position_key,
                                          angular ? "rad/s" : "m/s"));
  if (drive->has(position_key)) {
    joint.drive = DriveMode::position;
    joint.drive_target = drive->number(position_key) * (angular ? kDegree : 1);
  } else {
    joint.drive = DriveMode::velocity;
    joint.drive_target = drive->number("target_velocity");
  }
  joint.drive_max = drive->number(angular ? "max_torque" : "max_force", 0.0, Range::non_negative());
  joint.drive_compliance = drive->number("compliance", 0.0, Range::non_negative());
  drive->finish();
}

}  // namespace

void build_joints(const std::vector<JsonObject>& list, Model& model) {
  for (const JsonObject& j : list) {
    Joint joint;
    joint.name = j.string("name");
    for (const Joint& other : model.joints)
      if (other.name == joint.name) j.fail("name", fmt::format("another joint is already named '{}'", joint.name));
    const std::string type = j.choice("type", {"fixed", "spherical", "hinge", "prismatic", "distance"});
    joint.type = type == "fixed"       ? JointType::fixed
                 : type == "spherical" ? JointType::spherical
                 : type == "hinge"     ? JointType::hinge
                 : type == "prismatic" ? JointType::prismatic
                                       : JointType::distance;
    const auto& bodies = j.raw("bodies");
    if (!bodies.is_array() || bodies.size() != 2) j.fail("bodies", "expected two ends: [\"a\", \"b\"]");
    joint.ends = {read_end(j, bodies[0], 0, model), read_end(j, bodies[1], 1, model)};
    if (joint.ends[0].kind == BodyEndKind::world && joint.ends[1].kind == BodyEndKind::world)
      j.fail("bodies", "a joint needs at least one end that is not the world");
    if (joint.ends[0].kind == joint.ends[1].kind && joint.ends[0].index == joint.ends[1].index)
      j.fail("bodies", "a joint cannot connect a body to itself");
    const bool oriented_ends = joint.ends[0].kind != BodyEndKind::particle && joint.ends[1].kind != BodyEndKind::particle;

    // Anchors: one shared world point, or one per end.
    if (j.has("anchor") == j.has("anchors")) j.fail("anchor", "give exactly one of \"anchor\" (one world point) or \"anchors\" (one per end)");
    std::array<Vec3, 2> anchors;
    if (j.has("anchor")) {
      anchors[0] = anchors[1] = j.vec3("anchor");
    } else {
      const auto& raw = j.raw("anchors");
      if (!raw.is_array() || raw.size() != 2) j.fail("anchors", "expected two world points [[x, y, z], [x, y, z]]");
      for (int k = 0; k < 2; ++k) {
        const auto& point = raw[k];
        const bool numeric = point.is_array() && point.size() == 3 &&
                             std::all_of(point.begin(), point.end(), [](const auto& v) { return v.is_number(); });
        if (!numeric) j.fail("anchors", "expected two world points of three numbers each [[x, y, z], [x, y, z]]");
        anchors[k] = Vec3(point[0].get<Real>(), point[1].get<Real>(), point[2].get<Real>());
      }
    }
    const Vec3 axis_in = j.vec3("axis", Vec3::UnitX());
    if (axis_in.norm() <= 0) j.fail("axis", "the axis must not be zero");
    const Quat frame = frame_from_axis(axis_in.normalized());
    for (int k = 0; k < 2; ++k) attach(joint.ends[k], anchors[k], frame, model);

    const bool needs_frames = joint.type != JointType::distance &&
                              !(joint.type == JointType::spherical && !j.has("swing_deg") && !j.has("twist_deg"));
    if (needs_frames && !oriented_ends)
      j.fail("bodies", fmt::format("a {} joint needs orientations at both ends; a particle end allows spherical "
                                   "(without limits) and distance joints", type));

    joint.compliance = j.number("compliance", 0.0, Range::non_negative());
    joint.angular_compliance = j.number("angular_compliance", 0.0, Range::non_negative());
    joint.damping = j.number("damping", 0.0, Range::non_negative());
    joint.angular_damping = j.number("angular_damping", 0.0, Range::non_negative());

    switch (joint.type) {
      case JointType::hinge:
        if (j.has("limits_deg")) {
          const Vec2 r = read_degrees_range(j, "limits_deg");
          joint.limited = true;
          joint.lower = r.x();
          joint.upper = r.y();
        }
        break;
      case JointType::prismatic:
        if (j.has("limits")) {
          const Vec2 r = j.vec2("limits", Range::any());
          if (r.x() > r.y()) j.fail("limits", "the lower limit must not exceed the upper one");
          joint.limited = true;
          joint.lower = r.x();
          joint.upper = r.y();
        }
        break;
      case JointType::spherical:
        if (j.has("swing_deg")) {
          joint.swing_limited = true;
          joint.swing = j.number("swing_deg", Range::closed(0, 180)) * kDegree;
        }
        if (j.has("twist_deg")) {
          const Vec2 r = read_degrees_range(j, "twist_deg");
          joint.twist_limited = true;
          joint.twist_lower = r.x();
          joint.twist_upper = r.y();
        }
        break;
      case JointType::distance: {
        const Real rest = (end_world_point(joint.ends[0], model) - end_world_point(joint.ends[1], model)).norm();
        joint.limited = true;
        joint.lower = j.number("min", rest, Range::non_negative());
        joint.upper = j.number("max", std::max(rest, joint.lower), Range::non_negative());
        if (joint.lower > joint.upper) j.fail("min", "\"min\" must not exceed \"max\"");
        break;
      }
      case JointType::fixed: break;
    }
    read_drive(j, joint);
    // Joined bodies do not collide with each other unless asked to.
    if (!j.boolean("collide", false) && joint.ends[0].kind == BodyEndKind::body &&
        joint.ends[1].kind == BodyEndKind::body) {
      const Index a = joint.ends[0].index, b = joint.ends[1].index;
      model.rigid.pairs_without_contact.push_back({std::min(a, b), std::max(a, b)});
    }
    j.finish();
    model.joints.push_back(std::move(joint));
  }
  auto& pairs = model.rigid.pairs_without_contact;
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
}

}  // namespace moreau
