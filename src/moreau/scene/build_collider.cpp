#include "moreau/scene/object_builders.hpp"

namespace moreau {

void build_collider(const JsonObject& object, ObjectInfo& info, SceneBuildContext& ctx) {
  Collider c;
  const JsonObject shape = object.object("shape");
  const std::string type = shape.choice("type", {"plane", "box", "sphere", "capsule"});
  shape.expect_keys(type == "plane"    ? std::vector<std::string>{"type", "normal", "point", "offset"}
                    : type == "box"    ? std::vector<std::string>{"type", "center", "half_extents", "size", "rotation_deg"}
                    : type == "sphere" ? std::vector<std::string>{"type", "center", "radius"}
                                       : std::vector<std::string>{"type", "center", "radius", "half_height", "rotation_deg"});
  if (type == "plane") {
    c.shape = make_plane();
    const Vec3 n = shape.vec3("normal", Vec3::UnitY());
    if (n.norm() <= 0) shape.fail("normal", "the plane normal must not be zero");
    c.normal = n.normalized();
    if (shape.has("point") && shape.has("offset")) shape.fail("point", "give either \"point\" or \"offset\", not both");
    c.position = shape.has("point") ? shape.vec3("point") : Vec3(c.normal * shape.number("offset", 0.0));
  } else if (type == "box") {
    c.position = shape.vec3("center");
    if (shape.has("size") == shape.has("half_extents"))
      shape.fail("half_extents", "give exactly one of \"half_extents\" or \"size\" (m)");
    const Vec3 half_extents = shape.has("size") ? Vec3(0.5 * shape.vec3("size")) : shape.vec3("half_extents");
    if (half_extents.minCoeff() <= 0) shape.fail("half_extents", "every extent must be > 0");
    c.shape = make_box(half_extents);
    c.rotation = rotation_from_degrees(shape.vec3("rotation_deg", Vec3::Zero()));
  } else if (type == "sphere") {
    c.position = shape.vec3("center");
    c.shape = make_sphere(shape.number("radius", Range::positive()));
  } else {
    c.position = shape.vec3("center");
    const Real radius = shape.number("radius", Range::positive());
    c.shape = make_capsule(radius, shape.number("half_height", Range::non_negative()));
    c.rotation = rotation_from_degrees(shape.vec3("rotation_deg", Vec3::Zero()));
  }
  shape.finish();
  c.velocity = object.vec3("velocity", Vec3::Zero());
  c.inside = object.boolean("inside", false);
  if (c.inside && c.shape.type == ShapeType::plane)
    object.fail("inside", "a plane has no inside; use a box, sphere or capsule as a container");
  c.fluid_walls = object.boolean("fluid_walls", true);
  read_contact_material(object, c.static_friction, c.dynamic_friction, c.restitution);
  info.kind = ObjectKind::collider;
  info.collider = static_cast<Index>(ctx.model.colliders.size());
  info.static_friction = c.static_friction;
  info.dynamic_friction = c.dynamic_friction;
  info.restitution = c.restitution;
  ctx.model.colliders.push_back(c);
}

}  // namespace moreau
