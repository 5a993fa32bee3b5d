#pragma once
// Rigid bodies of the constraint engine (Mueller et al. 2020, "Detailed Rigid Body Simulation with
// Extended Position Based Dynamics"). A body's pose is its centre of mass x and the orientation q
// of its principal frame: a body-frame point r is at x + q r in the world. Inertia is diagonal in
// that frame. Colliders take part as kinematic bodies with infinite mass.
#include <vector>

#include "moreau/collision/shape.hpp"

namespace moreau {

enum class BodyMotion {
  dynamic,    // integrated under gravity and constraints
  fixed,      // never moves
  kinematic,  // moves with its prescribed velocity and angular velocity; infinite mass
};

/// One body as a builder describes it (RigidBodyModel::add fills every per-body array from it).
struct BodyDescription {
  Shape shape;
  Index object = -1;                           // owning scene object
  BodyMotion motion = BodyMotion::dynamic;
  Real mass = 0;                               // kg (0 for colliders)
  Vec3 inertia = Vec3::Zero();                 // kg m^2, principal
  Quat frame_in_shape = Quat::Identity();      // principal frame -> the frame the shape was given in
  Vec3 center_in_shape = Vec3::Zero();         // m
  Real static_friction = 0, dynamic_friction = 0, restitution = 0, adhesion = 0;
  Vec3 position = Vec3::Zero();                // m, centre of mass at t = 0
  Quat orientation = Quat::Identity();         // principal frame -> world at t = 0
  Vec3 velocity = Vec3::Zero(), angular_velocity = Vec3::Zero();  // m/s, rad/s (world)
};

struct RigidBodyModel {
  std::vector<Shape> body_shape;
  std::vector<Index> body_object;            // owning scene object
  std::vector<BodyMotion> body_motion;
  std::vector<Real> body_mass;               // kg (0 for colliders)
  std::vector<Real> body_inv_mass;           // 1/kg, 0 unless dynamic
  std::vector<Vec3> body_inv_inertia;        // 1/(kg m^2), principal, 0 unless dynamic
  std::vector<Vec3> body_inertia;            // kg m^2, principal
  std::vector<Quat> body_frame_in_shape;     // principal frame -> the frame the shape was given in
  std::vector<Vec3> body_center_in_shape;    // m, centre of mass in the frame the shape was given in
  std::vector<Real> body_static_friction, body_dynamic_friction, body_restitution;
  std::vector<Real> body_adhesion;  // N per contact point: the pull a contact holds under nmd
  std::vector<std::array<Index, 2>> pairs_without_contact;  // sorted (a < b): joined bodies
  std::vector<std::array<Index, 2>> particle_pairs_without_contact;  // sorted (body, particle): joined by a joint
  std::vector<Index> body_contact_group;     // bodies of one group never touch each other (a rod without
                                             // self-collision); -1 or past the end: none
  // Initial conditions (the state at t = 0).
  std::vector<Vec3> initial_position, initial_velocity, initial_angular_velocity;
  std::vector<Quat> initial_orientation;

  Index count() const { return static_cast<Index>(body_shape.size()); }
  /// Appends a body; its inverse mass and inertia are 0 unless it is dynamic. Returns its index.
  Index add(BodyDescription body);
  bool empty() const { return body_shape.empty(); }
  bool is_dynamic(Index b) const { return body_motion[b] == BodyMotion::dynamic; }
};

struct RigidBodyState {
  std::vector<Vec3> position;                 // m, centre of mass
  std::vector<Quat> orientation;              // principal frame -> world
  std::vector<Vec3> velocity;                 // m/s
  std::vector<Vec3> angular_velocity;         // rad/s, world frame

  void resize(Index n);
};

}  // namespace moreau
