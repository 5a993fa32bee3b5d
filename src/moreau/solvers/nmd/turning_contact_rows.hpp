#pragma once
// The turning rows of a contact at the velocity level where a side is a grain, a solid sphere
// that turns (the same contact as constraints/turning_contact.hpp at the position level).
//
// The contact's rows 0 to 2 (normal n from side j to side i, friction along t1 and t2) already
// hold the linear columns of both sides and a rigid body's angular ones. A grain side s turns at
// w_s and touches at the arm a_s from its centre: a_i = -r_i n, a_j = +r_j n, between two grains
// the radii scaled to the centre distance d, so that a_j - a_i = d n and the pair's impulses
// exert no net torque; against a rigid body the distance to the body's surface point, where the
// body's rows act (against a collider the radius). Its contact point moves at v_s + w_s x a_s, so the rates of the rows,
// e . (u_i - u_j) with u the contact point's velocity on each side, take
//   e . (w_s x a_s) = w_s . (a_s x e)        (+ for side i, - for side j)
// in the grain's spin columns: nothing in the normal row (a_s is along n), the arm's lever in the
// friction rows, so friction acts at the contact point and sets grains rolling. Three turning rows
// measure how the sides turn on each other, e . (w_i - w_j) for e = t1, t2 (rolling) and n
// (twisting), in a grain's spin columns and a rigid body's angular ones; colliders and particles
// that do not turn add nothing. They are dissipative rows (target 0, like friction) bounded
// together by the ball |l_roll| <= mu_r R* (l_n + F h): the constant rolling-resistance model
// (Ai, Chen, Rotter and Ooi 2011, model A), R* = r_i r_j / (r_i + r_j) between two grains, the
// grain's r against anything else, F a cohesive bond's pull.
//
// Projected Gauss-Seidel solves the friction rows and then the turning rows of a contact. Where
// the sides differ (a grain against the ground, a body or a smaller grain) the two couple through
// c = r_i I_i^-1 - r_j I_j^-1, and a sweep leaves c^2 / (D_friction D_turning) of their joint error
// (5/7 for a grain on the ground): slower than the rows of equal grains, which do not couple.
#include <array>

#include "moreau/solvers/nmd/nmd_system.hpp"

namespace moreau {

/// One side of a contact as its turning rows see it.
struct TurningSide {
  Index grain = -1;   // a particle that turns in this solve (VelocitySpace::turns), else -1
  Real arm = 0;       // m: from the grain's centre to the contact point
  int body_end = -1;  // the block's end that is a rigid body, whose angular columns turn, else -1
};

/// Adds the spin ends and the three turning rows to a contact block of rows 0 to 2 (made by
/// set_contact) when a side is a grain that turns; sides[0] is the side n points to, `rolling`
/// is mu_r R* (m). Returns false, leaving the input as it was, when neither side turns.
bool add_turning_rows(NmdBlockInput& in, const VelocitySpace& space, const std::array<TurningSide, 2>& sides,
                      const Vec3& n, const Vec3& t1, const Vec3& t2, Real rolling);

/// The same rows for two grains that both turn, in closed form (nmd_system.hpp, GrainPairRows):
/// makes a contact block of six rows over the ends (v_i, v_j, w_i, w_j), sized by
/// `resize(6, 4, false)` and made a contact by set_contact, a grain pair of arms r_i', r_j'.
void make_grain_pair(NmdBlockInput& in, const Vec3& n, const Vec3& t1, const Vec3& t2, Real arm_i, Real arm_j,
                     Real rolling);

}  // namespace moreau
