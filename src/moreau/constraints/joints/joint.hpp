#pragma once
// Joints between rigid bodies, particles and the world (Mueller et al. 2020, sec. 3.4): the data
// of one joint and what every solver asks of it.
//
// Every end carries an anchor r and a frame [x y z] (x: the hinge/twist/slide axis) in its body
// frame; for the world both are world-space; a particle has an anchor at its centre and no frame.
// With d = p_a - p_b the anchor offset (p = x + q r) and x_a, x_b the frames' x axes in the world,
// each type is a short list of row blocks (body_rows.hpp), one file per type:
//   fixed      fixed_joint.cpp      orientation (3 rows) and attachment d = 0 (3 rows)
//   hinge      hinge_joint.cpp      axis alignment (2), angle limits, drive, attachment (3)
//   spherical  spherical_joint.cpp  swing and twist limits, attachment (3)
//   prismatic  prismatic_joint.cpp  orientation (3), no sideways offset (2), slide limits, drive
//   distance   distance_joint.cpp   |d| in [min, max] (1)
//   rod        rod_joint.cpp        a Cosserat rod's junction: bend-twist (3) and stretch-shear (3),
//                                   each with a compliance per axis of the joint frame
// Adding a joint type: its file with a JointTypeRules, one line in joint_types.cpp, and its name
// in the scene builder.
#include <array>
#include <string>

#include "moreau/constraints/body_rows.hpp"
#include "moreau/constraints/substep_start.hpp"

namespace moreau {

struct State;

enum class JointType { fixed, spherical, hinge, prismatic, distance, rod };
enum class DriveMode { none, position, velocity };

struct JointEnd {
  BodyEndKind kind = BodyEndKind::world;
  Index index = -1;                      // rigid body or global particle index
  Vec3 anchor = Vec3::Zero();            // body frame (world for the world, zero for a particle)
  Quat frame = Quat::Identity();         // joint frame in the body frame (world for the world)

  BodyEnd body() const { return {kind, index}; }
};

struct Joint {
  std::string name;
  JointType type = JointType::spherical;
  std::array<JointEnd, 2> ends;
  Real compliance = 0;                   // m/N, positional rows
  Real angular_compliance = 0;           // rad/(N m), orientation rows
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
  Real damping_time = 0;                 // s: stiffness-proportional damping of compliant equality rows (rods)
  // Rod junctions: compliance per axis of the joint frame (x along the rod, y and z across it).
  Vec3 rod_compliance = Vec3::Zero();          // m/N: stretch along x, shear along y and z
  Vec3 rod_angular_compliance = Vec3::Zero();  // rad/(N m): twist about x, bending about y and z
  bool rod_pinned = false;                     // a pinned rod end: stretch-shear rows only, free to turn

  std::array<BodyEnd, 2> bodies() const { return {ends[0].body(), ends[1].body()}; }
};

/// The multipliers of one joint's rows, at fixed slots (BodyRows::slot).
struct JointSlot {
  static constexpr int position = 0;     // attachment (3) or a prismatic joint's sideways rows (2)
  static constexpr int orientation = 3;  // orientation (3) or hinge alignment (2)
  static constexpr int distance = 6;
  static constexpr int limit = 7;        // hinge angle or prismatic slide
  static constexpr int swing = 8;
  static constexpr int twist = 9;
  static constexpr int drive = 10;
  static constexpr int count = 11;
};
using JointMultipliers = std::array<Real, JointSlot::count>;

/// Which of a joint's rows to produce: all of them, only its equality rows (what the direct
/// tree solver takes, joint_tree.hpp), or all but those.
enum class JointRowSet { all, equality, all_but_equality };

/// A joint seen at the poses in `state`, read afresh for every block (a Gauss-Seidel sink moves
/// the bodies between blocks).
struct JointRowContext {
  const State& state;
  const Joint& joint;
  Real h = 0;                // s, the substep
  Real drive_start = 0;      // rad or m: the drive's coordinate at the substep start
  JointRowSet set = JointRowSet::all;
  const SubstepStart* start = nullptr;  // the poses at the substep start, for damped rows (position level)

  bool wants_equality() const { return set != JointRowSet::all_but_equality; }
  bool wants_others() const { return set != JointRowSet::equality; }
};

/// Largest positional violation (m) and angular violation (rad) of one joint.
struct JointError {
  Real position = 0, angle = 0;
};

/// The joint's row blocks at the context's poses, in the order a Gauss-Seidel pass solves them
/// (orientation rows first: they move the anchors).
void joint_rows(const JointRowContext& context, BodyRowSink& sink);

/// Equality rows of a joint the direct tree solver may take (0: none).
int direct_rows(const Joint& joint);

/// Whether the joint has rows besides its equality rows (limits, drives, a distance range).
bool has_other_rows(const Joint& joint);

/// Violation of one joint now.
JointError joint_error(const Joint& joint, const State& state);

/// Hinge angle (rad) or prismatic slide (m) now; 0 for other types.
Real joint_coordinate(const Joint& joint, const State& state);

}  // namespace moreau
