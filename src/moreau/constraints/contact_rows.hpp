#pragma once
// Constraint rows of one rigid contact manifold: what every solver reads from a contact.
//
// Per penetrating point j of the manifold (narrow_phase.hpp: the normal n from b to a, the surface
// points p_a = x_a + q_a core_a - r_a n and p_b = x_b + q_b core_b + r_b n), three point rows
// (body_rows.hpp: J_a = [d^T, (o_a x d)^T], J_b = -[d^T, (o_b x d)^T] for direction d at the
// points' offsets o from the centres), rigid (compliance 0):
//   row 3j      normal   C = (p_a - p_b) . n >= 0: a unilateral row, the force f_n >= 0
//   rows 3j+1,2 static   C = s . t_k = 0 for two tangents t_k, s the slip of the two material
//               friction points over the substep plus the slip left over since the point began to
//                        stick (rigid_contacts.hpp); bounded by the friction cone |f_t| <= mu_s f_n
// Points not in penetration have no rows for a position-level solver (Mueller et al. 2020, sec.
// 3.5, handles a contact when its depth is negative); a velocity-level solver also takes the
// separated points of the manifold (speculative contacts: a gap C > 0 that may close in a step).
#include <array>
#include <cmath>

#include "moreau/collision/narrow_phase.hpp"
#include "moreau/constraints/body_rows.hpp"
#include "moreau/constraints/substep_start.hpp"

namespace moreau {

struct RigidManifold;
struct RigidContactPoint;
struct RigidBodyState;

struct ContactRows {
  static constexpr int kMaxPoints = 4, kMaxRows = 3 * kMaxPoints;
  std::array<BodyEnd, 2> end;
  int points = 0;                              // rows 3j (normal), 3j + 1 and 3j + 2 (tangents)
  std::array<int, kMaxPoints> point{};         // the manifold's point in slot j
  std::array<Vec3, kMaxRows> direction, offset_a, offset_b;  // world; a point's rows share offsets
  std::array<Real, kMaxRows> C{};              // m
  Real static_friction = 0;                    // mu_s of the cone

  int size() const { return 3 * points; }
};

/// Two unit tangents t1, t2 = n x t1 completing the unit normal n (the same for a point in every
/// pass, so static friction rows keep their directions).
inline Vec3 contact_tangent(const Vec3& n) {
  return (std::abs(n.x()) < 0.6 ? Vec3::UnitX() : Vec3::UnitY()).cross(n).normalized();
}

/// A manifold point at the bodies' poses: the unit normal n (b to a), the surface points
/// p_a = x_a + q_a core_a - r_a n and p_b = x_b + q_b core_b + r_b n, and their separation
/// C = (p_a - p_b) . n (negative in penetration).
struct ContactPointAtPoses {
  Vec3 normal, point_a, point_b;
  Real separation;
};
ContactPointAtPoses contact_point_at_poses(NormalFrame frame, const ContactGeometry& c, const Pose& pose_a,
                                          const Pose& pose_b);

/// Which points of a manifold get rows: those in penetration, or every point (speculative).
enum class ContactPoints { penetrating, all };

/// The manifold's rows at the bodies' current poses, the slip measured from `start`. Records on
/// each point its normal and world offsets now, and on points with rows their material
/// (body-frame) points, which the velocity pass and the stuck slip read.
ContactRows manifold_rows(const RigidManifold& manifold, RigidContactPoint* points, const RigidBodyState& bodies,
                          const SubstepStart& start, ContactPoints which = ContactPoints::penetrating);

}  // namespace moreau
