#pragma once
// Projected Gauss-Seidel on one rigid manifold's rows (constraints/contact_rows.hpp), at the
// position level (depth and static friction) and at the velocity level (restitution and dynamic
// friction), with the rows of the manifold's points solved together.
//
// Mueller et al. 2020 project point by point; for a box resting on four corners that lifts the
// far corner each time the near one is pushed, the box rocks, and the first corner's static
// friction must hold the whole box on a quarter of the load: a box on a 30 degree incline with
// mu = 0.7 then crept 12 mm in 2 s. Solved as a block it holds.
//
// A block is swept until a sweep moves no row's value by more than kBlockTolerance of the block's
// scale plus a floor (1e-8 m in the position pass, 1e-8 m/s in the velocity pass), or
// kMaxBlockSweeps sweeps. The block is a convex problem, so converged sweeps give the same body
// motion whatever the order of the rows; three fixed sweeps did not: a box sliding down a slope
// went 4 % too far or 2 % too short depending on the slope's direction, and turned. (Converged,
// the 210-box pyramid costs 15 ms per step against 7.7 ms with three sweeps; performance.md.) The
// cap is a guard, rarely reached: in the first 5 s, by no position block and by 7 of 1.07 million
// velocity blocks of the pyramid and 100 of 2.2 million of the 1000 boxes (a block then keeps its
// last sweep's impulses).
#include <array>

#include "moreau/constraints/contact_rows.hpp"

namespace moreau {

inline constexpr int kFirstSweeps = 3;  // position pass: enough to tell resting from sliding blocks
inline constexpr int kMaxBlockSweeps = 200;
inline constexpr Real kBlockTolerance = 1e-9, kPositionFloor = 1e-8, kVelocityFloor = 1e-8;

using RowValues = std::array<Real, ContactRows::kMaxRows>;
using BlockMatrix = std::array<RowValues, ContactRows::kMaxRows>;

/// A body's inverse mass and world inverse inertia, fetched once per manifold (zero for the world,
/// fixed and kinematic bodies).
struct InverseMass {
  Real linear = 0;
  Mat3 angular = Mat3::Zero();
};

/// Effective-mass matrix of the rows (direction d_r at offsets o_a,r, o_b,r), shared by the
/// position and velocity blocks:
///   K_rs = d_r.d_s (1/m_a + 1/m_b) + (o_a,r x d_r).I_a^-1 (o_a,s x d_s) + (same for b).
BlockMatrix effective_mass_block(const InverseMass& a, const InverseMass& b, const ContactRows& rows);

/// The position-level block: x the rows' multipliers (one manifold, this projection) from
///   C + K x = 0 (rows at rest),  x_n >= 0 complementary to C_n + (K x)_n,
///   |x_t| <= mu_s x_n, else x_t = 0 (the point slides: the velocity pass applies dynamic friction).
/// Also says whether the manifold slides (see the .cpp).
struct PositionBlockSolution {
  RowValues x;
  bool sliding = false;
};
PositionBlockSolution solve_position_block(const ContactRows& rows, const BlockMatrix& K);

/// The velocity-level block: (K x + v0)_n = target_n, (K x + v0)_t = 0 subject to |x_t| <= bound
/// (a disc per point), swept until a sweep changes no row's velocity by more than kBlockTolerance
/// of `speed` plus kVelocityFloor.
RowValues solve_velocity_block(const BlockMatrix& K, const RowValues& v0, const RowValues& target,
                               const RowValues& bound, int rows, Real speed);

}  // namespace moreau
