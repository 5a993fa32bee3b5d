#pragma once
// Constraint rows between two bodies: what every solver reads from a joint.
//
// A block of R <= 3 scalar rows C_r acting on two ends. An end is a rigid body (centre x and
// orientation q), a particle (a body without rotation) or the world. A body moves by dx and by a
// world-space rotation vector dtheta (q += 1/2 [dtheta, 0] q, Mueller et al. 2020 eq. 9), so the
// gradient of the rows with respect to one end is an R x 6 block [dC/dx, dC/dtheta]:
//   C           the row values (m, rad, or the joint's own measure),
//   jacobian[e] the R x 6 gradient of end e (the angular columns are ignored for particles),
//   compliance  alpha per row (m/N for positional rows, rad/(N m) for angular rows); 0 is rigid,
//   lower/upper bounds on each row's generalised force (N or N m): (-inf, inf) for an equality,
//               one side 0 for a limit that may only push, +-max for a drive of bounded force.
//               A solver converts them to its multiplier: XPBD's lambda is the force times h^2.
//   slot        where the block's multipliers live in the joint's multipliers (JointMultipliers),
//   damping_time, motion
//               stiffness-proportional (Kelvin-Voigt) damping of compliant rows: a force
//               -(damping_time / alpha) dC/dt besides -C / alpha. A position-level solver needs
//               `motion`, J times the ends' motion since the substep start (empty when the rows
//               were read without the start poses: no damping then); a velocity-level solver
//               takes damping_time as its relaxation time.
//   velocity_drive, target_velocity
//               a velocity drive's single row: dC/dt should be target_velocity. A position-level
//               solver takes its C (the drive's coordinate minus the start plus h times the
//               target); a velocity-level solver takes the rate.
// Two row shapes cover every joint (Mueller 2020, sec. 3.3):
//   point rows     C grows when a's point at world offset r_a moves along unit n (b's at r_b
//                  against it): J_a = [n^T, (r_a x n)^T], J_b = -[n^T, (r_b x n)^T];
//   rotation rows  C grows when a turns about unit n: J_a = [0, n^T], J_b = [0, -n^T].
#include <array>
#include <limits>

#include "moreau/math/types.hpp"

namespace moreau {

enum class BodyEndKind { world, body, particle };

/// One end of a row block: a rigid body, a particle (global index) or the world.
struct BodyEnd {
  BodyEndKind kind = BodyEndKind::world;
  Index index = -1;
};

struct BodyRows {
  static constexpr int kMaxRows = 3;
  using Vector = Eigen::Matrix<Real, Eigen::Dynamic, 1, 0, kMaxRows, 1>;
  using Jacobian = Eigen::Matrix<Real, Eigen::Dynamic, 6, 0, kMaxRows, 6>;

  std::array<BodyEnd, 2> end;
  Vector C, compliance, lower, upper;
  std::array<Jacobian, 2> jacobian;
  int slot = 0;
  Real damping_time = 0;  // s
  Vector motion;          // m or rad, per row; empty: unknown
  bool velocity_drive = false;
  Real target_velocity = 0;

  int size() const { return static_cast<int>(C.size()); }

  /// R bilateral rows between the two ends whose values and Jacobians the caller writes whole.
  static BodyRows bilateral(const std::array<BodyEnd, 2>& ends, int rows, int slot, Real compliance) {
    BodyRows r;
    r.end = ends;
    r.slot = slot;
    r.C.resize(rows);
    r.compliance.setConstant(rows, compliance);
    r.lower.setConstant(rows, -std::numeric_limits<Real>::infinity());
    r.upper.setConstant(rows, std::numeric_limits<Real>::infinity());
    for (Jacobian& j : r.jacobian) j.resize(rows, 6);
    return r;
  }
  /// R zeroed rows between the two ends: no gradient, rigid, bilateral.
  static BodyRows zero(const std::array<BodyEnd, 2>& ends, int rows, int slot) {
    BodyRows r = bilateral(ends, rows, slot, 0);
    r.C.setZero();
    for (Jacobian& j : r.jacobian) j.setZero();
    return r;
  }

  /// Makes row r a point row along n at offsets ra, rb (see the file comment).
  void set_point_row(int r, const Vec3& n, const Vec3& ra, const Vec3& rb) {
    jacobian[0].row(r) << n.transpose(), ra.cross(n).transpose();
    jacobian[1].row(r) << -n.transpose(), -rb.cross(n).transpose();
  }
  /// Makes row r a rotation row about n.
  void set_rotation_row(int r, const Vec3& n) {
    jacobian[0].row(r) << 0, 0, 0, n.transpose();
    jacobian[1].row(r) << 0, 0, 0, -n.transpose();
  }
  /// Lets row r push only one way: a limit whose value must stay >= 0 (at_least) or <= 0.
  void make_unilateral(int r, bool at_least) {
    if (at_least)
      lower(r) = 0;
    else
      upper(r) = 0;
  }
};

/// The XPBD update of damped rows (Macklin, Mueller, Chentanez 2016, eq. 26) in the form of an
/// undamped one: with gamma = damping_time / h, (1 + gamma) J W J^T dl + alpha~ dl =
/// -(C + alpha~ l + gamma J dx) divided by 1 + gamma is the undamped update with
/// C' = (C + gamma J dx) / (1 + gamma) and alpha~' = alpha~ / (1 + gamma). Rows without damping
/// or without `motion` are left as they are.
inline void apply_xpbd_damping(const BodyRows& rows, Real h, BodyRows::Vector& C, BodyRows::Vector& alpha_tilde) {
  if (rows.damping_time <= 0 || rows.motion.size() != rows.size()) return;
  const Real gamma = rows.damping_time / h;
  C = (C + gamma * rows.motion) / (1 + gamma);
  alpha_tilde /= 1 + gamma;
}

/// Receives the row blocks of a constraint in order. A Gauss-Seidel solver projects each block as
/// it arrives (the next block is evaluated at the corrected poses); a global solver collects them.
class BodyRowSink {
 public:
  virtual void take(const BodyRows& rows) = 0;

 protected:
  ~BodyRowSink() = default;
};

}  // namespace moreau
