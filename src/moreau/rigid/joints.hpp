#pragma once
// Joints between rigid bodies, particles and the world (Mueller et al. 2020, sec. 3.4), each a
// set of positional and angular XPBD corrections (body_handle.hpp) between attachment frames.
//
// Every end carries an anchor r and a frame [x y z] (x: the hinge/twist/slide axis) in its body
// frame; for the world both are world-space; a particle has an anchor at its centre and no frame.
// With d = p_a - p_b the anchor offset (p = x + q r) and u_a, u_b the frames' axes in the world:
//   attachment (all but distance)  C = d = 0 (3 rows, one block)  compliance alpha [m/N]
//   fixed orientation              C = 2 vec(q_fa q_fb^-1) = 0    alpha_angular [rad/(N m)], 3 rows
//   hinge alignment                C = x_b x x_a = 0              2 rows, perpendicular to x_a
//   hinge angle  phi = atan2((y_a x y_b) . x_a, y_a . y_b)        (b relative to a about x_a)
//     limits     phi in [lower, upper]; drive  C = phi - phi_target, phi_target = phi_start + h
//                omega_target for a velocity drive; |lambda| / h^2 <= max torque
//   swing limit  angle(x_a, x_b) <= swing (about x_a x x_b);  twist limits about (x_a + x_b)/|.|
//   prismatic    C = d - (d . x_a) x_a = 0 and the slide s = -(d . x_a) in [lower, upper]; fixed
//                orientation; a drive to s_target or at a velocity, |lambda|/h^2 <= max force
//   distance     |d| in [min, max]
// Sign convention of every correction: C grows when body a moves (rotates) along (about) +n.
// Damping (velocity pass, Mueller 2020 eq. 32): the anchors' relative velocity and the bodies'
// relative angular velocity lose the fraction min(c h, 1) per substep, c in 1/s.
#include <string>
#include <vector>

#include "moreau/math/types.hpp"

namespace moreau {

struct Model;
struct State;

enum class JointType { fixed, spherical, hinge, prismatic, distance };
enum class JointEndKind { world, body, particle };
enum class DriveMode { none, position, velocity };

struct JointEnd {
  JointEndKind kind = JointEndKind::world;
  Index index = -1;                      // rigid body or global particle index
  Vec3 anchor = Vec3::Zero();            // body frame (world for the world, zero for a particle)
  Quat frame = Quat::Identity();         // joint frame in the body frame (world for the world)
};

struct Joint {
  std::string name;
  JointType type = JointType::spherical;
  std::array<JointEnd, 2> ends;
  Real compliance = 0;                   // m/N, positional part
  Real angular_compliance = 0;           // rad/(N m), orientation part
  Real damping = 0, angular_damping = 0; // 1/s
  // Hinge angle (rad) or prismatic slide (m) limits; distance joints use them as [min, max] (m).
  bool limited = false;
  Real lower = 0, upper = 0;
  // Spherical joints.
  bool swing_limited = false, twist_limited = false;
  Real swing = 0, twist_lower = 0, twist_upper = 0;  // rad
  // Drive (hinge, prismatic).
  DriveMode drive = DriveMode::none;
  Real drive_target = 0;                 // rad or m (position drive); rad/s or m/s (velocity drive)
  Real drive_max = 0;                    // N m or N; 0 = unlimited
  Real drive_compliance = 0;             // rad/(N m) or m/N
};

/// Multipliers of one joint within a substep.
struct JointLambdas {
  Vec3 position = Vec3::Zero(), orientation = Vec3::Zero();
  Real distance = 0, limit = 0, swing = 0, twist = 0, drive = 0;
};

/// Fills `lambdas` with zeros (start of a substep) and records each drive's starting angle/slide.
void reset_joints(const Model& model, State& state);

/// One Gauss-Seidel pass over all joints, in scene order; call from one thread.
void project_joints(const Model& model, State& state, Real h);

/// Joint damping (velocity pass).
void damp_joints(const Model& model, State& state, Real h);

/// Largest positional violation (m) and angular violation (rad) of one joint now.
struct JointError {
  Real position = 0, angle = 0;
};
JointError joint_error(const Model& model, const State& state, Index joint);

/// Hinge angle (rad) or prismatic slide (m) now; 0 for other types.
Real joint_coordinate(const Model& model, const State& state, Index joint);

}  // namespace moreau
