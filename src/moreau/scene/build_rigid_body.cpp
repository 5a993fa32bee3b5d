// "kind": "rigid_body" objects, and the colliders that rigid bodies collide with.
#include <fmt/format.h>

#include <Eigen/Geometry>
#include <stdexcept>

#include "moreau/geometry/mesh_readers.hpp"
#include "moreau/collision/mesh_shape.hpp"
#include "moreau/scene/object_builders.hpp"

namespace moreau {

namespace {

// "orientation": [w, x, y, z] (a unit quaternion, normalised) or "rotation_deg": [rx, ry, rz].
Quat read_orientation(const JsonObject& object) {
  if (object.has("orientation") && object.has("rotation_deg"))
    object.fail("orientation", "give either \"orientation\" (a quaternion [w, x, y, z]) or \"rotation_deg\", not both");
  if (object.has("orientation")) {
    const auto& raw = object.raw("orientation");
    if (!raw.is_array() || raw.size() != 4 || !std::all_of(raw.begin(), raw.end(), [](const auto& v) { return v.is_number(); }))
      object.fail("orientation", "expected a quaternion [w, x, y, z] of four numbers");
    const Quat q(raw[0].get<Real>(), raw[1].get<Real>(), raw[2].get<Real>(), raw[3].get<Real>());
    if (q.norm() < 1e-12) object.fail("orientation", "the quaternion must not be zero");
    return q.normalized();
  }
  return Quat(rotation_from_degrees(object.vec3("rotation_deg", Vec3::Zero())));
}

Shape read_shape(const JsonObject& shape, const SceneBuildContext& ctx) {
  const std::string type = shape.choice("type", {"sphere", "box", "capsule", "cylinder", "convex_hull", "triangle_mesh"});
  shape.expect_keys(type == "sphere"          ? std::vector<std::string>{"type", "radius"}
                    : type == "box"           ? std::vector<std::string>{"type", "half_extents", "size"}
                    : type == "convex_hull"   ? std::vector<std::string>{"type", "mesh", "scale"}
                    : type == "triangle_mesh" ? std::vector<std::string>{"type", "mesh", "scale", "thickness"}
                                              : std::vector<std::string>{"type", "radius", "half_height"});
  Shape s;
  if (type == "sphere") {
    s = make_sphere(shape.number("radius", Range::positive()));
  } else if (type == "box") {
    if (shape.has("size") == shape.has("half_extents"))
      shape.fail("half_extents", "give exactly one of \"half_extents\" or \"size\" (m)");
    const Vec3 e = shape.has("size") ? Vec3(0.5 * shape.vec3("size")) : shape.vec3("half_extents");
    if (e.minCoeff() <= 0) shape.fail(shape.has("size") ? "size" : "half_extents", "every extent must be > 0");
    s = make_box(e);
  } else if (type == "capsule" || type == "cylinder") {
    const Real r = shape.number("radius", Range::positive());
    const Real hh = shape.number("half_height", type == "capsule" ? Range::non_negative() : Range::positive());
    s = type == "capsule" ? make_capsule(r, hh) : make_cylinder(r, hh);
  } else {
    const std::string file = resolve_path(ctx, shape.string("mesh"));
    const Real scale = shape.number("scale", 1.0, Range::positive());
    TriangleMesh mesh;
    try {
      mesh = read_obj_triangles(file);
    } catch (const std::exception& e) {
      shape.fail("mesh", e.what());
    }
    for (Vec3& v : mesh.vertices) v *= scale;
    if (type == "triangle_mesh") {
      // A one-sided shell with a slab of solid `thickness` behind each triangle (mesh_shape.hpp).
      const Real thickness = shape.number("thickness", 0.05, Range::positive());
      try {
        return make_triangle_mesh(make_mesh_shape(mesh, thickness));
      } catch (const std::invalid_argument& e) {
        shape.fail("mesh", fmt::format("'{}': {}", file, e.what()));
      }
    }
    s.type = ShapeType::convex_hull;
    try {
      s.polyhedron = convex_hull(mesh.vertices);
    } catch (const std::invalid_argument& e) {
      shape.fail("mesh", fmt::format("'{}': {}", file, e.what()));
    }
  }
  shape.finish();
  return s;
}

}  // namespace

void build_rigid_body(const JsonObject& object, ObjectInfo& info, SceneBuildContext& ctx) {
  RigidBodyModel& m = ctx.model.rigid;
  const JsonObject shape_json = object.object("shape");
  Shape shape = read_shape(shape_json, ctx);
  MassProperties props = mass_properties(shape);
  // Principal frame: the shape's own frame for primitives, its inertia eigenvectors for hulls.
  const Mat3 principal = move_to_principal_frame(shape, props);

  const bool fixed = object.boolean("fixed", false), kinematic = object.boolean("kinematic", false);
  if (fixed && kinematic) object.fail("kinematic", "a body is either fixed or kinematic, not both");
  Real mass = 0;
  Vec3 inertia = Vec3::Zero();
  if (shape.type == ShapeType::triangle_mesh) {
    // A mesh has no volume to give it mass: it only moves as prescribed.
    if (!fixed && !kinematic)
      shape_json.fail("type", "a triangle_mesh body must be \"fixed\" or \"kinematic\"; a dynamic body needs a "
                              "solid shape (a \"convex_hull\" of the same OBJ, or a primitive)");
    if (object.has("mass") || object.has("density"))
      object.fail(object.has("mass") ? "mass" : "density", "a triangle_mesh body has no mass (it is fixed or kinematic)");
  } else {
    if (object.has("mass") && object.has("density")) object.fail("mass", "give either \"mass\" (kg) or \"density\" (kg/m^3), not both");
    if (object.has("mass")) mass = object.number("mass", Range::positive());
    else mass = object.number("density", 1000.0, Range::positive()) * props.volume;
    inertia = props.inertia.diagonal() * (mass / props.volume);
  }

  const Vec3 position = object.vec3("position");
  const Quat orientation = read_orientation(object);
  Real mu_s = 0.5, mu_k = 0.5, e = 0;
  read_contact_material(object, mu_s, mu_k, e);

  info.kind = ObjectKind::rigid_body;
  info.body = m.count();
  info.static_friction = mu_s;
  info.dynamic_friction = mu_k;
  info.restitution = e;
  info.fluid_coupling = object.boolean("fluid_coupling", true);
  const bool dynamic = !fixed && !kinematic;
  m.body_shape.push_back(std::move(shape));
  m.body_object.push_back(static_cast<Index>(ctx.model.objects.size()));
  m.body_motion.push_back(fixed ? BodyMotion::fixed : kinematic ? BodyMotion::kinematic : BodyMotion::dynamic);
  m.body_mass.push_back(mass);
  m.body_inv_mass.push_back(dynamic ? 1 / mass : 0);
  m.body_inertia.push_back(inertia);
  m.body_inv_inertia.push_back(dynamic ? Vec3(inertia.cwiseInverse()) : Vec3(Vec3::Zero()));
  m.body_frame_in_shape.push_back(Quat(principal));
  m.body_center_in_shape.push_back(props.center);
  m.body_static_friction.push_back(mu_s);
  m.body_dynamic_friction.push_back(mu_k);
  m.body_restitution.push_back(e);
  // "position" places the shape's own origin; the state holds the centre of mass and the
  // principal frame.
  m.initial_position.push_back(position + orientation * props.center);
  m.initial_orientation.push_back((orientation * Quat(principal)).normalized());
  const Vec3 v = object.vec3("velocity", Vec3::Zero()), w = object.vec3("angular_velocity", Vec3::Zero());
  if (fixed && (v != Vec3::Zero() || w != Vec3::Zero()))
    object.fail("velocity", "a fixed body cannot move; use \"kinematic\": true for prescribed motion");
  // A body's velocity is that of its centre of mass: v_com = v_origin + w x (com - origin).
  m.initial_velocity.push_back(v + w.cross(orientation * props.center));
  m.initial_angular_velocity.push_back(w);
}

void add_colliders_as_bodies(Model& model) {
  RigidBodyModel& m = model.rigid;
  if (m.empty()) return;
  for (size_t o = 0; o < model.objects.size(); ++o) {
    ObjectInfo& info = model.objects[o];
    if (info.kind != ObjectKind::collider) continue;
    const Collider& c = model.colliders[info.collider];
    auto add = [&](Shape shape, const Vec3& position, const Quat& orientation) {
      m.body_shape.push_back(std::move(shape));
      m.body_object.push_back(static_cast<Index>(o));
      m.body_motion.push_back(c.velocity == Vec3::Zero() ? BodyMotion::fixed : BodyMotion::kinematic);
      m.body_mass.push_back(0);
      m.body_inv_mass.push_back(0);
      m.body_inertia.push_back(Vec3::Zero());
      m.body_inv_inertia.push_back(Vec3::Zero());
      m.body_frame_in_shape.push_back(Quat::Identity());
      m.body_center_in_shape.push_back(Vec3::Zero());
      m.body_static_friction.push_back(c.static_friction);
      m.body_dynamic_friction.push_back(c.dynamic_friction);
      m.body_restitution.push_back(c.restitution);
      m.initial_position.push_back(position);
      m.initial_orientation.push_back(orientation);
      m.initial_velocity.push_back(c.velocity);
      m.initial_angular_velocity.push_back(Vec3::Zero());
    };
    // A plane is the half-space y <= 0 of a frame whose y axis is the normal.
    auto plane = [&](const Vec3& point, const Vec3& normal) {
      add(make_plane(), point, Quat::FromTwoVectors(Vec3::UnitY(), normal));
    };
    if (info.body < 0) info.body = m.count();
    switch (c.shape.type) {
      case ShapeType::plane: plane(c.position, c.normal); break;
      case ShapeType::box:
        if (c.inside) {
          // A container: its six walls, each a plane facing inwards.
          for (int axis = 0; axis < 3; ++axis)
            for (int side : {-1, 1}) {
              const Vec3 n = c.rotation.col(axis) * Real(-side);
              plane(c.position + c.rotation.col(axis) * (side * c.shape.half_extents[axis]), n);
            }
        } else {
          add(c.shape, c.position, Quat(c.rotation));
        }
        break;
      case ShapeType::sphere:
        if (!c.inside) add(c.shape, c.position, Quat::Identity());
        break;
      case ShapeType::capsule:
        if (!c.inside) add(c.shape, c.position, Quat(c.rotation));
        break;
      default: unsupported_collider_shape(c.shape.type);
    }
  }
}

}  // namespace moreau
