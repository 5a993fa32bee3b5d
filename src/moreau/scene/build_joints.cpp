// The scene's "joints" list (see joints.hpp for the constraints and docs/scene-format.md).
#include <fmt/format.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <optional>

#include "moreau/scene/spec_builders.hpp"

namespace moreau {

namespace {

constexpr Real kDegree = kPi / 180;

// One end: "world", a rigid body's name, or a particle of a cloth or soft body.
JointEndSpec read_end(const JsonObject& joint, const nlohmann::json& value, int slot) {
  JointEndSpec end;
  if (value.is_string()) {
    end.object = value.get<std::string>();
    return end;
  }
  if (!value.is_object()) joint.fail("bodies", fmt::format("bodies[{}] must be a name or an object", slot));
  const JsonObject ref(value, joint.path_of("bodies") + fmt::format("[{}]", slot), joint.file());
  end.object = ref.string("object");
  if (ref.has("vertex")) end.vertex = read_integer(ref, "vertex");
  end.nearest = read_optional_vector(ref, "nearest");
  if (!end.vertex && !end.nearest) ref.fail("vertex", "give exactly one of \"vertex\" or \"nearest\"");
  ref.finish();
  return end;
}

// A rod's centreline point by "vertex" (0 to the segment count) or the rest point nearest "nearest".
Index rod_point_index(const JointEndSpec& spec, const SpecPlace& ref, const RodModel& rod) {
  if (spec.vertex && spec.nearest) ref.fail("vertex", "give exactly one of \"vertex\" or \"nearest\"");
  if (spec.vertex) return ref.integer("vertex", *spec.vertex, 0, rod.points() - 1);
  return rod.nearest_rest_point(ref.vector("nearest", *spec.nearest));
}

// The rest position of a joint end that is a rod's centreline point, if it is one.
std::optional<Vec3> rod_end_point(const JointEndSpec& spec, const SpecPlace& joint, int slot, const Model& model) {
  const Index o = model.find_object(spec.object);
  if (o < 0 || model.objects[o].kind != ObjectKind::rod || !(spec.vertex || spec.nearest)) return std::nullopt;
  const RodModel& rod = model.rods[model.objects[o].rod];
  return rod.rest_points[rod_point_index(spec, joint.at(fmt::format("bodies[{}]", slot)), rod)];
}

// The model's end: the world, a body, or one particle (by vertex or the one nearest a point).
JointEnd resolve_end(const JointEndSpec& spec, const SpecPlace& joint, int slot, const Model& model) {
  JointEnd end;
  const std::string where = fmt::format("bodies[{}]", slot);
  const bool particle_end = spec.vertex || spec.nearest;
  if (!particle_end) {
    if (spec.object == "world") return end;
    const Index o = model.find_object(spec.object);
    if (o < 0 || model.objects[o].kind != ObjectKind::rigid_body)
      joint.fail("bodies", fmt::format("{} is '{}', which is not a rigid body of this scene; give \"world\", a rigid "
                                       "body's name or {{\"object\": <cloth, soft body or rod>, \"vertex\": i}}",
                                       where, spec.object));
    end.kind = BodyEndKind::body;
    end.index = model.objects[o].body;
    return end;
  }
  const SpecPlace ref = joint.at(where);
  const Index o = model.find_object(spec.object);
  if (o >= 0 && model.objects[o].kind == ObjectKind::rod) {
    // A rod's centreline point: the segment it starts (the last point ends the last segment).
    const RodModel& rod = model.rods[model.objects[o].rod];
    end.kind = BodyEndKind::body;
    end.index = rod.first_body + rod.segment_of_point(rod_point_index(spec, ref, rod));
    return end;
  }
  if (o < 0 || !model.objects[o].has_particles())
    ref.fail("object", fmt::format("'{}' is not a cloth, soft body or rod of this scene", spec.object));
  const ObjectInfo& info = model.objects[o];
  const Index initial_end = model.initial_particle_end(o);  // an emitter's grains cannot hold a joint
  if (initial_end == info.particle_begin)
    ref.fail("object", fmt::format("'{}' has no particle at the start (its grains come from an emitter)", spec.object));
  end.kind = BodyEndKind::particle;
  if (spec.vertex && spec.nearest) ref.fail("vertex", "give exactly one of \"vertex\" or \"nearest\"");
  if (spec.vertex) {
    end.index = info.particle_begin + ref.integer("vertex", *spec.vertex, 0, initial_end - info.particle_begin - 1);
  } else {
    const Vec3 p = ref.vector("nearest", *spec.nearest);
    Index best = info.particle_begin;
    for (Index i = info.particle_begin; i < initial_end; ++i)
      if ((model.particle_rest_position[i] - p).squaredNorm() < (model.particle_rest_position[best] - p).squaredNorm())
        best = i;
    end.index = best;
  }
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

// A limit pair [lower, upper] in degrees, checked and in radians.
Vec2 degrees_range(const SpecPlace& j, const std::string& field, const Vector2& value) {
  const Vec2 r = j.pair(field, value, Range::closed(-180, 180));
  if (r.x() > r.y()) j.fail(field, "the lower limit must not exceed the upper one");
  return r * kDegree;
}

JointDrive read_drive(const JsonObject& drive, bool angular) {
  JointDrive d;
  const std::string position_key = angular ? "target_angle_deg" : "target_position";
  (angular ? d.target_angle_deg : d.target_position) = read_optional_number(drive, position_key);
  d.target_velocity = read_optional_number(drive, "target_velocity");
  d.max_force = drive.number(angular ? "max_torque" : "max_force", d.max_force);
  d.compliance = drive.number("compliance", d.compliance);
  drive.finish();
  return d;
}

void add_drive(const JointDrive& spec, const SpecPlace& place, Joint& joint) {
  const bool angular = joint.type == JointType::hinge;
  if (!angular && joint.type != JointType::prismatic) place.fail("drive", "only hinge and prismatic joints have drives");
  const SpecPlace drive = place.at("drive");
  const std::string position_key = angular ? "target_angle_deg" : "target_position";
  const std::optional<double>& target = angular ? spec.target_angle_deg : spec.target_position;
  if ((angular ? spec.target_position : spec.target_angle_deg).has_value())
    drive.fail(angular ? "target_position" : "target_angle_deg", fmt::format("a {} drive takes \"{}\"", angular ? "hinge" : "prismatic", position_key));
  if (target.has_value() == spec.target_velocity.has_value())
    drive.fail(position_key, fmt::format("give exactly one of \"{}\" or \"target_velocity\" ({})", position_key,
                                         angular ? "rad/s" : "m/s"));
  if (target) {
    joint.drive = DriveMode::position;
    joint.drive_target = drive.number(position_key, *target) * (angular ? kDegree : 1);
  } else {
    joint.drive = DriveMode::velocity;
    joint.drive_target = drive.number("target_velocity", *spec.target_velocity);
  }
  joint.drive_max = drive.number(angular ? "max_torque" : "max_force", spec.max_force, Range::non_negative());
  joint.drive_compliance = drive.number("compliance", spec.compliance, Range::non_negative());
}

const std::vector<std::string> kJointTypes{"fixed", "spherical", "hinge", "prismatic", "distance"};

}  // namespace

JointSpec read_joint(const JsonObject& j) {
  JointSpec spec;
  spec.name = j.string("name");
  spec.type = j.choice("type", kJointTypes);
  const auto& bodies = j.raw("bodies");
  if (!bodies.is_array() || bodies.size() != 2) j.fail("bodies", "expected two ends: [\"a\", \"b\"]");
  spec.bodies = {read_end(j, bodies[0], 0), read_end(j, bodies[1], 1)};
  // Anchors: one shared world point, or one per end (add_joint wants exactly one).
  spec.anchor = read_optional_vector(j, "anchor");
  if (j.has("anchors")) {
    const auto& raw = j.raw("anchors");
    if (!raw.is_array() || raw.size() != 2) j.fail("anchors", "expected two world points [[x, y, z], [x, y, z]]");
    std::array<Vector3, 2> anchors;
    for (int k = 0; k < 2; ++k) {
      const auto& point = raw[k];
      const bool numeric = point.is_array() && point.size() == 3 &&
                           std::all_of(point.begin(), point.end(), [](const auto& v) { return v.is_number(); });
      if (!numeric) j.fail("anchors", "expected two world points of three numbers each [[x, y, z], [x, y, z]]");
      anchors[k] = {point[0].get<Real>(), point[1].get<Real>(), point[2].get<Real>()};
    }
    spec.anchors = anchors;
  }
  spec.axis = read_vector(j, "axis", spec.axis);
  spec.compliance = j.number("compliance", spec.compliance);
  spec.angular_compliance = j.number("angular_compliance", spec.angular_compliance);
  spec.damping = j.number("damping", spec.damping);
  spec.angular_damping = j.number("angular_damping", spec.angular_damping);
  if (spec.type == "hinge") spec.limits_deg = read_optional_pair(j, "limits_deg");
  if (spec.type == "prismatic") spec.limits = read_optional_pair(j, "limits");
  if (spec.type == "spherical") {
    spec.swing_deg = read_optional_number(j, "swing_deg");
    spec.twist_deg = read_optional_pair(j, "twist_deg");
  }
  if (spec.type == "distance") {
    spec.min = read_optional_number(j, "min");
    spec.max = read_optional_number(j, "max");
  }
  if (j.has("drive")) {
    if (spec.type != "hinge" && spec.type != "prismatic") j.fail("drive", "only hinge and prismatic joints have drives");
    spec.drive = read_drive(j.object("drive"), spec.type == "hinge");
  }
  spec.collide = j.boolean("collide", spec.collide);
  j.finish();
  return spec;
}

void add_joint(const JointSpec& spec, const SpecPlace& j, Model& model) {
  Joint joint;
  joint.name = spec.name;
  if (joint.name.empty()) j.fail("name", "a joint needs a name");
  for (const Joint& other : model.joints)
    if (other.name == joint.name)
      j.fail("name", fmt::format("another joint is already named '{}' (a rod names its own junctions "
                                 "<rod>.junction<k>, <rod>.start and <rod>.end)",
                                 joint.name));
  const std::string& type = j.choice("type", spec.type, kJointTypes);
  joint.type = type == "fixed"       ? JointType::fixed
               : type == "spherical" ? JointType::spherical
               : type == "hinge"     ? JointType::hinge
               : type == "prismatic" ? JointType::prismatic
                                     : JointType::distance;
  joint.ends = {resolve_end(spec.bodies[0], j, 0, model), resolve_end(spec.bodies[1], j, 1, model)};
  if (joint.ends[0].kind == BodyEndKind::world && joint.ends[1].kind == BodyEndKind::world)
    j.fail("bodies", "a joint needs at least one end that is not the world");
  if (joint.ends[0].kind == joint.ends[1].kind && joint.ends[0].index == joint.ends[1].index)
    j.fail("bodies", "a joint cannot connect a body to itself (a rod's points k and k + 1 are the two ends of one "
                     "rigid segment)");
  const bool oriented_ends = joint.ends[0].kind != BodyEndKind::particle && joint.ends[1].kind != BodyEndKind::particle;

  // A rod's point is its end's anchor unless one is given (the other end takes it too, if it is
  // not a rod's point itself).
  const std::array<std::optional<Vec3>, 2> rod_point{rod_end_point(spec.bodies[0], j, 0, model),
                                                      rod_end_point(spec.bodies[1], j, 1, model)};
  if (spec.anchor && spec.anchors) j.fail("anchor", "give exactly one of \"anchor\" (one world point) or \"anchors\" (one per end)");
  if (!spec.anchor && !spec.anchors && !rod_point[0] && !rod_point[1])
    j.fail("anchor", "give exactly one of \"anchor\" (one world point) or \"anchors\" (one per end)");
  std::array<Vec3, 2> anchors;
  if (spec.anchor) anchors[0] = anchors[1] = j.vector("anchor", *spec.anchor);
  else if (!spec.anchors)
    for (int k = 0; k < 2; ++k) anchors[k] = rod_point[k] ? *rod_point[k] : *rod_point[1 - k];
  else anchors = {j.vector("anchors", (*spec.anchors)[0]), j.vector("anchors", (*spec.anchors)[1])};
  const Vec3 axis_in = j.vector("axis", spec.axis);
  if (axis_in.norm() <= 0) j.fail("axis", "the axis must not be zero");
  const Quat frame = frame_from_axis(axis_in.normalized());
  for (int k = 0; k < 2; ++k) attach(joint.ends[k], anchors[k], frame, model);

  const bool needs_frames = joint.type != JointType::distance &&
                            !(joint.type == JointType::spherical && !spec.swing_deg && !spec.twist_deg);
  if (needs_frames && !oriented_ends)
    j.fail("bodies", fmt::format("a {} joint needs orientations at both ends; a particle end allows spherical "
                                 "(without limits) and distance joints", type));

  joint.compliance = j.number("compliance", spec.compliance, Range::non_negative());
  joint.angular_compliance = j.number("angular_compliance", spec.angular_compliance, Range::non_negative());
  joint.damping = j.number("damping", spec.damping, Range::non_negative());
  joint.angular_damping = j.number("angular_damping", spec.angular_damping, Range::non_negative());

  // Each limit belongs to one joint type.
  auto only_for = [&](bool given, const char* field, JointType owner, const char* owner_name) {
    if (given && joint.type != owner) j.fail(field, fmt::format("only a {} joint takes \"{}\"", owner_name, field));
  };
  only_for(spec.limits_deg.has_value(), "limits_deg", JointType::hinge, "hinge");
  only_for(spec.limits.has_value(), "limits", JointType::prismatic, "prismatic");
  only_for(spec.swing_deg.has_value(), "swing_deg", JointType::spherical, "spherical");
  only_for(spec.twist_deg.has_value(), "twist_deg", JointType::spherical, "spherical");
  only_for(spec.min.has_value(), "min", JointType::distance, "distance");
  only_for(spec.max.has_value(), "max", JointType::distance, "distance");
  switch (joint.type) {
    case JointType::hinge:
      if (spec.limits_deg) {
        const Vec2 r = degrees_range(j, "limits_deg", *spec.limits_deg);
        joint.limited = true;
        joint.lower = r.x();
        joint.upper = r.y();
      }
      break;
    case JointType::prismatic:
      if (spec.limits) {
        const Vec2 r = j.pair("limits", *spec.limits);
        if (r.x() > r.y()) j.fail("limits", "the lower limit must not exceed the upper one");
        joint.limited = true;
        joint.lower = r.x();
        joint.upper = r.y();
      }
      break;
    case JointType::spherical:
      if (spec.swing_deg) {
        joint.swing_limited = true;
        joint.swing = j.number("swing_deg", *spec.swing_deg, Range::closed(0, 180)) * kDegree;
      }
      if (spec.twist_deg) {
        const Vec2 r = degrees_range(j, "twist_deg", *spec.twist_deg);
        joint.twist_limited = true;
        joint.twist_lower = r.x();
        joint.twist_upper = r.y();
      }
      break;
    case JointType::distance: {
      const Real rest = (end_world_point(joint.ends[0], model) - end_world_point(joint.ends[1], model)).norm();
      joint.limited = true;
      joint.lower = j.number("min", spec.min.value_or(rest), Range::non_negative());
      joint.upper = j.number("max", spec.max.value_or(std::max(rest, joint.lower)), Range::non_negative());
      if (joint.lower > joint.upper) j.fail("min", "\"min\" must not exceed \"max\"");
      break;
    }
    case JointType::fixed:
    case JointType::rod: break;  // rods make their own (build_rod.cpp)
  }
  if (spec.drive) add_drive(*spec.drive, j, joint);
  // Joined bodies, and a body and a particle joined, do not collide with each other unless asked to.
  if (!spec.collide && joint.ends[0].kind == BodyEndKind::body && joint.ends[1].kind == BodyEndKind::body) {
    const Index a = joint.ends[0].index, b = joint.ends[1].index;
    model.rigid.pairs_without_contact.push_back({std::min(a, b), std::max(a, b)});
  }
  for (int e = 0; e < 2; ++e)
    if (!spec.collide && joint.ends[e].kind == BodyEndKind::body && joint.ends[1 - e].kind == BodyEndKind::particle)
      model.rigid.particle_pairs_without_contact.push_back({joint.ends[e].index, joint.ends[1 - e].index});
  model.joints.push_back(std::move(joint));
}

void finish_joints(Model& model) {
  for (auto* pairs : {&model.rigid.pairs_without_contact, &model.rigid.particle_pairs_without_contact}) {
    std::sort(pairs->begin(), pairs->end());
    pairs->erase(std::unique(pairs->begin(), pairs->end()), pairs->end());
  }
}

}  // namespace moreau
