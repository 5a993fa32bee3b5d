// "kind": "collider": a fixed or kinematic plane, box, sphere or capsule.
#include <fmt/format.h>

#include "moreau/scene/spec_builders.hpp"

namespace moreau {

ColliderSpec read_collider(const JsonObject& object) {
  ColliderSpec spec;
  const JsonObject shape = object.object("shape");
  const std::string type = shape.choice("type", {"plane", "box", "sphere", "capsule"});
  shape.expect_keys(type == "plane"    ? std::vector<std::string>{"type", "normal", "point", "offset"}
                    : type == "box"    ? std::vector<std::string>{"type", "center", "half_extents", "size", "rotation_deg"}
                    : type == "sphere" ? std::vector<std::string>{"type", "center", "radius"}
                                       : std::vector<std::string>{"type", "center", "radius", "half_height", "rotation_deg"});
  if (type == "plane") {
    PlaneShape plane;
    plane.normal = read_vector(shape, "normal", plane.normal);
    const Vec3 n = to_vec3(plane.normal);  // checked by add_collider
    if (shape.has("point") && shape.has("offset")) shape.fail("point", "give either \"point\" or \"offset\", not both");
    plane.point = shape.has("point") ? to_vector3(shape.vec3("point"))
                                     : to_vector3(n.normalized() * shape.number("offset", 0.0));
    spec.shape = plane;
  } else if (type == "box") {
    spec.center = to_vector3(shape.vec3("center"));
    if (shape.has("size") == shape.has("half_extents"))
      shape.fail("half_extents", "give exactly one of \"half_extents\" or \"size\" (m)");
    if (shape.has("size") && !(shape.vec3("size").minCoeff() > 0)) shape.fail("size", "every extent must be > 0");
    spec.shape = BoxShape{to_vector3(shape.has("size") ? Vec3(0.5 * shape.vec3("size")) : shape.vec3("half_extents"))};
    spec.rotation_deg = read_vector(shape, "rotation_deg", spec.rotation_deg);
  } else if (type == "sphere") {
    spec.center = to_vector3(shape.vec3("center"));
    spec.shape = SphereShape{shape.number("radius")};
  } else {
    spec.center = to_vector3(shape.vec3("center"));
    CapsuleShape capsule;
    capsule.radius = shape.number("radius");
    capsule.half_height = shape.number("half_height");
    spec.shape = capsule;
    spec.rotation_deg = read_vector(shape, "rotation_deg", spec.rotation_deg);
  }
  shape.finish();
  spec.velocity = read_vector(object, "velocity", spec.velocity);
  spec.inside = object.boolean("inside", spec.inside);
  spec.fluid_walls = object.boolean("fluid_walls", spec.fluid_walls);
  spec.fluid_friction = object.number("fluid_friction", spec.fluid_friction);
  spec.temperature = read_optional_number(object, "temperature");
  spec.until = read_optional_number(object, "until");
  spec.contact = read_contact_material(object);
  return spec;
}

void add_collider(const ColliderSpec& spec, const SpecPlace& place, ObjectInfo& info, SceneBuildContext& ctx) {
  Collider c;
  const SpecPlace shape = place.at("shape");
  if (const auto* plane = std::get_if<PlaneShape>(&spec.shape)) {
    c.shape = make_plane();
    const Vec3 n = shape.vector("normal", plane->normal);
    if (n.norm() <= 0) shape.fail("normal", "the plane normal must not be zero");
    c.normal = n.normalized();
    c.position = shape.vector("point", plane->point);
  } else if (const auto* box = std::get_if<BoxShape>(&spec.shape)) {
    const Vec3 half_extents = shape.vector("half_extents", box->half_extents);
    if (half_extents.minCoeff() <= 0) shape.fail("half_extents", "every extent must be > 0");
    c.shape = make_box(half_extents);
  } else if (const auto* sphere = std::get_if<SphereShape>(&spec.shape)) {
    c.shape = make_sphere(shape.number("radius", sphere->radius, Range::positive()));
  } else if (const auto* capsule = std::get_if<CapsuleShape>(&spec.shape)) {
    const Real radius = shape.number("radius", capsule->radius, Range::positive());
    c.shape = make_capsule(radius, shape.number("half_height", capsule->half_height, Range::non_negative()));
  } else {
    shape.fail("type", "a collider is a plane, box, sphere or capsule; cylinders, convex hulls and triangle meshes "
                       "are rigid bodies with \"fixed\": true");
  }
  // A plane is placed by its point and normal, a sphere has no orientation: neither takes the
  // fields that would be silently ignored.
  const bool rotated = c.shape.type == ShapeType::box || c.shape.type == ShapeType::capsule;
  if (c.shape.type == ShapeType::plane) {
    if (spec.center != Vector3{0, 0, 0}) shape.fail("center", "a plane is placed by its \"point\" and \"normal\"");
  } else {
    c.position = shape.vector("center", spec.center);
  }
  if (rotated) c.rotation = rotation_from_degrees(shape.vector("rotation_deg", spec.rotation_deg));
  else if (spec.rotation_deg != Vector3{0, 0, 0}) shape.fail("rotation_deg", "only a box or a capsule collider is rotated");
  c.velocity = place.vector("velocity", spec.velocity);
  c.inside = spec.inside;
  if (c.inside && c.shape.type == ShapeType::plane)
    place.fail("inside", "a plane has no inside; use a box, sphere or capsule as a container");
  c.fluid_walls = spec.fluid_walls;
  c.fluid_friction = place.number("fluid_friction", spec.fluid_friction, Range::closed(0, 1));
  if (spec.temperature) {
    c.temperature = place.number("temperature", *spec.temperature, Range::positive());
    if (!c.fluid_walls)
      place.fail("temperature", "a collider with \"fluid_walls\": false has no wall samples to exchange heat with the "
                                "fluids; remove \"temperature\" or sample the walls");
  }
  if (c.fluid_friction > 0 && !c.fluid_walls)
    place.fail("fluid_friction", "a collider with \"fluid_walls\": false has no wall samples to carry the fluid's wall "
                                 "friction; remove \"fluid_friction\" or sample the walls");
  if (spec.until) c.until = place.number("until", *spec.until, Range::non_negative());
  set_contact_material(spec.contact, place, info);
  c.static_friction = info.static_friction;
  c.dynamic_friction = info.dynamic_friction;
  c.restitution = info.restitution;
  c.adhesion = info.adhesion;
  info.kind = ObjectKind::collider;
  info.collider = static_cast<Index>(ctx.model.colliders.size());
  ctx.model.colliders.push_back(c);
}

}  // namespace moreau
