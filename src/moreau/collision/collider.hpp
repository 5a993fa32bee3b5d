#pragma once
// Colliders: fixed or kinematic (moving with a prescribed constant velocity) shapes that
// particles, fluids and rigid bodies collide with. A collider's shape is a plane, box, sphere or
// capsule of the one shape type rigid bodies use (shape.hpp), so a collider joins the rigid
// contacts as a body of infinite mass. For particles each shape answers one question: the signed
// distance from a point to its surface and the outward normal there.
#include <cmath>
#include <limits>
#include <optional>
#include <string>

#include "moreau/collision/shape.hpp"

namespace moreau {

struct Collider {
  Shape shape = make_plane();         // plane, box, sphere or capsule, in the collider's frame
  Vec3 position = Vec3::Zero();       // m: plane point, box/sphere center, capsule center at t = 0
  Mat3 rotation = Mat3::Identity();   // collider frame -> world (box, capsule)
  Vec3 velocity = Vec3::Zero();       // m/s, kinematic translation
  Vec3 normal = Vec3::UnitY();        // plane normal (unit, world)
  Real static_friction = 0.5;         // mu_s
  Real dynamic_friction = 0.5;        // mu_k
  Real restitution = 0;               // e
  Real adhesion = 0;                  // N per contact point with a rigid body or a particle (nmd)
  bool inside = false;                // a container: the solid is outside the shape (a tank keeps particles in)
  bool fluid_walls = true;            // sampled with wall particles for the fluid density
  Real fluid_friction = 0;            // the fluid's wall shear: 0 free slip, 1 no slip (fluid_viscosity.hpp)
  std::optional<Real> temperature;    // K: the wall holds the fluids at its surface at it; none: insulating (fluid_heat.hpp)
  Real until = std::numeric_limits<Real>::infinity();  // s: removed at this time (particles only)

  Vec3 position_at(Real time) const { return position + time * velocity; }
  /// Still there for a step starting at `time`: a collider with `until` is gone from the first step
  /// that starts at it or later (to a nanosecond, as step times are sums of dt).
  bool present_at(Real time) const { return time < until - 1e-9; }
  /// Is removed at some time (`until`).
  bool removable() const { return std::isfinite(until); }
  /// Moves or disappears: the grains on it may not sleep.
  bool changes() const { return !velocity.isZero() || removable(); }
};

/// The four shapes above are the ones a collider takes (the scene builder makes no other); a
/// switch over a collider's shape ends with this for the rest.
[[noreturn]] void unsupported_collider_shape(ShapeType type);

struct ColliderDistance {
  Real distance;  // m, negative inside
  Vec3 normal;    // outward unit normal at the closest surface point
};

/// Signed distance from x to the collider whose reference point is at `center` (its position at
/// the time of the query).
ColliderDistance collider_distance(const Collider& c, const Vec3& center, const Vec3& x);

/// The collider's surfaces closer to x than `reach` (written to `out`, the count returned): the
/// nearest one (collider_distance), or, in a box container, each wall of the up to three that a
/// point near an edge or corner is close to (one per axis, the nearer of its two faces).
int collider_surfaces_within(const Collider& c, const Vec3& center, const Vec3& x, Real reach, ColliderDistance out[3]);

/// The point nearest to x that is at least `gap` away from the collider's solid (its position at
/// the time of the query is `center`). A single push along the distance normal is that point for
/// every solid shape and for round containers; in a box container a point near an edge or corner
/// is too close to two or three walls at once, so there the local coordinates are clamped to the
/// box shrunk by `gap`.
Vec3 keep_clear_of_collider(const Collider& c, const Vec3& center, const Vec3& x, Real gap);

}  // namespace moreau
