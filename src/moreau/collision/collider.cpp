#include "moreau/collision/collider.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace moreau {

void unsupported_collider_shape(ShapeType type) {
  throw std::logic_error("a collider is a plane, box, sphere or capsule, not shape type " +
                         std::to_string(static_cast<int>(type)));
}

namespace {

ColliderDistance box_distance(const Vec3& half, const Vec3& q) {
  // q in the box frame. Outside: distance to the clamped point; inside: to the nearest face.
  const Vec3 excess = q.cwiseAbs() - half;
  if (excess.maxCoeff() > 0) {
    const Vec3 outside = excess.cwiseMax(0.0);
    Vec3 n(std::copysign(outside.x(), q.x()), std::copysign(outside.y(), q.y()), std::copysign(outside.z(), q.z()));
    const Real d = n.norm();
    return {d, n / d};
  }
  int axis = 0;
  excess.maxCoeff(&axis);
  Vec3 n = Vec3::Zero();
  n[axis] = q[axis] >= 0 ? 1.0 : -1.0;
  return {excess[axis], n};
}

ColliderDistance sphere_distance(const Vec3& center, Real radius, const Vec3& x) {
  const Vec3 d = x - center;
  const Real r = d.norm();
  if (r <= 0) return {-radius, Vec3::UnitY()};
  return {r - radius, d / r};
}

}  // namespace

namespace {

ColliderDistance solid_distance(const Collider& c, const Vec3& center, const Vec3& x) {
  switch (c.shape.type) {
    case ShapeType::plane:
      return {c.normal.dot(x - center), c.normal};
    case ShapeType::sphere:
      return sphere_distance(center, c.shape.radius, x);
    case ShapeType::box: {
      const ColliderDistance local = box_distance(c.shape.half_extents, c.rotation.transpose() * (x - center));
      return {local.distance, c.rotation * local.normal};
    }
    case ShapeType::capsule: {
      const Vec3 axis = c.rotation.col(1);
      const Real s = std::clamp(axis.dot(x - center), -c.shape.half_height, c.shape.half_height);
      return sphere_distance(center + s * axis, c.shape.radius, x);
    }
    default: unsupported_collider_shape(c.shape.type);
  }
}

}  // namespace

Vec3 keep_clear_of_collider(const Collider& c, const Vec3& center, const Vec3& x, Real gap) {
  if (c.inside && c.shape.type == ShapeType::box) {
    const Vec3 limit = (c.shape.half_extents.array() - gap).max(0.0);
    const Vec3 q = c.rotation.transpose() * (x - center);
    const Vec3 clamped = q.cwiseMax(-limit).cwiseMin(limit);
    return clamped == q ? x : Vec3(center + c.rotation * clamped);
  }
  const ColliderDistance d = collider_distance(c, center, x);
  return d.distance < gap ? Vec3(x + (gap - d.distance) * d.normal) : x;
}

int collider_surfaces_within(const Collider& c, const Vec3& center, const Vec3& x, Real reach, ColliderDistance out[3]) {
  if (c.inside && c.shape.type == ShapeType::box) {
    const Vec3 q = c.rotation.transpose() * (x - center);
    int count = 0;
    for (int axis = 0; axis < 3; ++axis) {
      const Real side = q[axis] >= 0 ? 1 : -1;  // the nearer face of this axis
      const Real distance = c.shape.half_extents[axis] - side * q[axis];
      if (distance >= reach) continue;
      Vec3 normal = Vec3::Zero();
      normal[axis] = -side;  // away from the wall, into the container
      out[count++] = {distance, c.rotation * normal};
    }
    return count;
  }
  out[0] = collider_distance(c, center, x);
  return out[0].distance < reach ? 1 : 0;
}

ColliderDistance collider_distance(const Collider& c, const Vec3& center, const Vec3& x) {
  const ColliderDistance d = solid_distance(c, center, x);
  if (c.inside) return {-d.distance, -d.normal};  // the solid is the complement of the shape
  return d;
}

}  // namespace moreau
