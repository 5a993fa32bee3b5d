// "kind": "rigid_body" objects, and the colliders that rigid bodies collide with.
#include <fmt/format.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "moreau/geometry/mesh_readers.hpp"
#include "moreau/collision/mesh_shape.hpp"
#include "moreau/scene/spec_builders.hpp"

namespace moreau {

namespace {

ShapeSpec read_shape(const JsonObject& shape) {
  const std::string type = shape.choice("type", {"sphere", "box", "capsule", "cylinder", "convex_hull", "triangle_mesh"});
  shape.expect_keys(type == "sphere"          ? std::vector<std::string>{"type", "radius"}
                    : type == "box"           ? std::vector<std::string>{"type", "half_extents", "size"}
                    : type == "convex_hull"   ? std::vector<std::string>{"type", "mesh", "scale"}
                    : type == "triangle_mesh" ? std::vector<std::string>{"type", "mesh", "scale", "thickness"}
                                              : std::vector<std::string>{"type", "radius", "half_height"});
  ShapeSpec s;
  if (type == "sphere") {
    s = SphereShape{shape.number("radius")};
  } else if (type == "box") {
    if (shape.has("size") == shape.has("half_extents"))
      shape.fail("half_extents", "give exactly one of \"half_extents\" or \"size\" (m)");
    if (shape.has("size") && !(shape.vec3("size").minCoeff() > 0)) shape.fail("size", "every extent must be > 0");
    s = BoxShape{to_vector3(shape.has("size") ? Vec3(0.5 * shape.vec3("size")) : shape.vec3("half_extents"))};
  } else if (type == "capsule" || type == "cylinder") {
    const Real r = shape.number("radius"), hh = shape.number("half_height");
    if (type == "capsule") s = CapsuleShape{r, hh};
    else s = CylinderShape{r, hh};
  } else if (type == "convex_hull") {
    ConvexHullShape hull;
    hull.mesh = shape.string("mesh");
    hull.scale = shape.number("scale", hull.scale);
    s = hull;
  } else {
    TriangleMeshShape mesh;
    mesh.mesh = shape.string("mesh");
    mesh.scale = shape.number("scale", mesh.scale);
    mesh.thickness = shape.number("thickness", mesh.thickness);
    s = mesh;
  }
  shape.finish();
  return s;
}

// An OBJ surface for a hull or a mesh shape, scaled.
TriangleMesh read_shape_mesh(const std::string& file, Real scale, const SpecPlace& place) {
  TriangleMesh mesh;
  try {
    mesh = read_obj_triangles(file);
  } catch (const std::exception& e) {
    place.fail("mesh", e.what());
  }
  for (Vec3& v : mesh.vertices) v *= scale;
  return mesh;
}

Shape make_body_shape(const ShapeSpec& spec, const SpecPlace& shape, const SceneBuildContext& ctx) {
  if (const auto* sphere = std::get_if<SphereShape>(&spec)) return make_sphere(shape.number("radius", sphere->radius, Range::positive()));
  if (const auto* box = std::get_if<BoxShape>(&spec)) {
    const Vec3 e = shape.vector("half_extents", box->half_extents);
    if (e.minCoeff() <= 0) shape.fail("half_extents", "every extent must be > 0");
    return make_box(e);
  }
  if (const auto* capsule = std::get_if<CapsuleShape>(&spec))
    return make_capsule(shape.number("radius", capsule->radius, Range::positive()),
                        shape.number("half_height", capsule->half_height, Range::non_negative()));
  if (const auto* cylinder = std::get_if<CylinderShape>(&spec))
    return make_cylinder(shape.number("radius", cylinder->radius, Range::positive()),
                         shape.number("half_height", cylinder->half_height, Range::positive()));
  if (const auto* mesh_shape = std::get_if<TriangleMeshShape>(&spec)) {
    const std::string file = resolve_path(ctx, mesh_shape->mesh);
    const TriangleMesh mesh = read_shape_mesh(file, shape.number("scale", mesh_shape->scale, Range::positive()), shape);
    // A one-sided shell with a slab of solid `thickness` behind each triangle (mesh_shape.hpp).
    const Real thickness = shape.number("thickness", mesh_shape->thickness, Range::positive());
    try {
      return make_triangle_mesh(make_mesh_shape(mesh, thickness));
    } catch (const std::invalid_argument& e) {
      shape.fail("mesh", fmt::format("'{}': {}", file, e.what()));
    }
  }
  if (const auto* hull = std::get_if<ConvexHullShape>(&spec)) {
    const std::string file = resolve_path(ctx, hull->mesh);
    const TriangleMesh mesh = read_shape_mesh(file, shape.number("scale", hull->scale, Range::positive()), shape);
    Shape s;
    s.type = ShapeType::convex_hull;
    try {
      s.polyhedron = convex_hull(mesh.vertices);
    } catch (const std::invalid_argument& e) {
      shape.fail("mesh", fmt::format("'{}': {}", file, e.what()));
    }
    return s;
  }
  shape.fail("type", "a plane is a collider, not a rigid body; give a box, sphere, capsule, cylinder, convex_hull or "
                     "triangle_mesh");
}

// "orientation": a unit quaternion [w, x, y, z] (normalised), or "rotation_deg".
Quat body_orientation(const RigidBodySpec& spec, const SpecPlace& place) {
  if (!spec.orientation) return Quat(rotation_from_degrees(place.vector("rotation_deg", spec.rotation_deg)));
  if (spec.rotation_deg != Vector3{0, 0, 0})
    place.fail("orientation", "give either \"orientation\" (a quaternion [w, x, y, z]) or \"rotation_deg\", not both");
  const auto& w = *spec.orientation;
  for (double c : w)
    if (!std::isfinite(c)) place.fail("orientation", "expected a quaternion [w, x, y, z] of four finite numbers");
  const Quat q(w[0], w[1], w[2], w[3]);
  if (q.norm() < 1e-12) place.fail("orientation", "the quaternion must not be zero");
  return q.normalized();
}

}  // namespace

RigidBodySpec read_rigid_body(const JsonObject& object) {
  RigidBodySpec spec;
  spec.shape = read_shape(object.object("shape"));
  spec.mass = read_optional_number(object, "mass");
  spec.density = read_optional_number(object, "density");
  spec.fixed = object.boolean("fixed", spec.fixed);
  spec.kinematic = object.boolean("kinematic", spec.kinematic);
  spec.position = to_vector3(object.vec3("position"));
  if (object.has("orientation") && object.has("rotation_deg"))
    object.fail("orientation", "give either \"orientation\" (a quaternion [w, x, y, z]) or \"rotation_deg\", not both");
  if (object.has("orientation")) {
    const auto& raw = object.raw("orientation");
    if (!raw.is_array() || raw.size() != 4 || !std::all_of(raw.begin(), raw.end(), [](const auto& v) { return v.is_number(); }))
      object.fail("orientation", "expected a quaternion [w, x, y, z] of four numbers");
    spec.orientation = Quaternion{raw[0].get<Real>(), raw[1].get<Real>(), raw[2].get<Real>(), raw[3].get<Real>()};
  }
  spec.rotation_deg = read_vector(object, "rotation_deg", spec.rotation_deg);
  spec.velocity = read_vector(object, "velocity", spec.velocity);
  spec.angular_velocity = read_vector(object, "angular_velocity", spec.angular_velocity);
  spec.contact = read_contact_material(object);
  spec.fluid_coupling = object.boolean("fluid_coupling", spec.fluid_coupling);
  spec.fluid_friction = object.number("fluid_friction", spec.fluid_friction);
  return spec;
}

void add_rigid_body(const RigidBodySpec& spec, const SpecPlace& place, ObjectInfo& info, SceneBuildContext& ctx) {
  RigidBodyModel& m = ctx.model.rigid;
  Shape shape = make_body_shape(spec.shape, place.at("shape"), ctx);
  MassProperties props = mass_properties(shape);
  // Principal frame: the shape's own frame for primitives, its inertia eigenvectors for hulls.
  const Mat3 principal = move_to_principal_frame(shape, props);

  const bool fixed = spec.fixed, kinematic = spec.kinematic;
  if (fixed && kinematic) place.fail("kinematic", "a body is either fixed or kinematic, not both");
  Real mass = 0;
  Vec3 inertia = Vec3::Zero();
  if (shape.type == ShapeType::triangle_mesh) {
    // A mesh has no volume to give it mass: it only moves as prescribed.
    if (!fixed && !kinematic)
      place.at("shape").fail("type", "a triangle_mesh body must be \"fixed\" or \"kinematic\"; a dynamic body needs a "
                                     "solid shape (a \"convex_hull\" of the same OBJ, or a primitive)");
    if (spec.mass || spec.density)
      place.fail(spec.mass ? "mass" : "density", "a triangle_mesh body has no mass (it is fixed or kinematic)");
  } else {
    if (spec.mass && spec.density) place.fail("mass", "give either \"mass\" (kg) or \"density\" (kg/m^3), not both");
    if (spec.mass) mass = place.number("mass", *spec.mass, Range::positive());
    else mass = place.number("density", spec.density.value_or(1000.0), Range::positive()) * props.volume;
    inertia = props.inertia.diagonal() * (mass / props.volume);
  }

  const Vec3 position = place.required_vector("position", spec.position);
  const Quat orientation = body_orientation(spec, place);
  set_contact_material(spec.contact, place, info);
  const Real mu_s = info.static_friction, mu_k = info.dynamic_friction, e = info.restitution;

  info.kind = ObjectKind::rigid_body;
  info.body = m.count();
  info.body_count = 1;
  set_fluid_coupling(spec.fluid_coupling, spec.fluid_friction, place, info);
  const Vec3 v = place.vector("velocity", spec.velocity), w = place.vector("angular_velocity", spec.angular_velocity);
  if (fixed && (v != Vec3::Zero() || w != Vec3::Zero()))
    place.fail("velocity", "a fixed body cannot move; use \"kinematic\": true for prescribed motion");
  BodyDescription body;
  body.shape = std::move(shape);
  body.object = static_cast<Index>(ctx.model.objects.size());
  body.motion = fixed ? BodyMotion::fixed : kinematic ? BodyMotion::kinematic : BodyMotion::dynamic;
  body.mass = mass;
  body.inertia = inertia;
  body.frame_in_shape = Quat(principal);
  body.center_in_shape = props.center;
  body.static_friction = mu_s;
  body.dynamic_friction = mu_k;
  body.restitution = e;
  body.adhesion = info.adhesion;
  // "position" places the shape's own origin; the state holds the centre of mass and the
  // principal frame.
  body.position = position + orientation * props.center;
  body.orientation = (orientation * Quat(principal)).normalized();
  // A body's velocity is that of its centre of mass: v_com = v_origin + w x (com - origin).
  body.velocity = v + w.cross(orientation * props.center);
  body.angular_velocity = w;
  m.add(std::move(body));
}

void add_colliders_as_bodies(Model& model) {
  RigidBodyModel& m = model.rigid;
  if (m.empty()) return;
  for (size_t o = 0; o < model.objects.size(); ++o) {
    ObjectInfo& info = model.objects[o];
    if (info.kind != ObjectKind::collider) continue;
    const Collider& c = model.colliders[info.collider];
    auto add = [&](Shape shape, const Vec3& position, const Quat& orientation) {
      BodyDescription body;
      body.shape = std::move(shape);
      body.object = static_cast<Index>(o);
      body.motion = c.velocity == Vec3::Zero() ? BodyMotion::fixed : BodyMotion::kinematic;
      body.static_friction = c.static_friction;
      body.dynamic_friction = c.dynamic_friction;
      body.restitution = c.restitution;
      body.adhesion = c.adhesion;
      body.position = position;
      body.orientation = orientation;
      body.velocity = c.velocity;
      m.add(std::move(body));
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
