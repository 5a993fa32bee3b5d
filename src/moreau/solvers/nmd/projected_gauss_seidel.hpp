#pragma once
// Projected Gauss-Seidel over the blocks of an NMD system (Lacoursiere 2007; Andrews, Erleben,
// Ferguson 2022, "Contact and Friction Simulation for Computer Graphics", sec. on PGS).
//
// u = M^-1 G^T l is kept in the velocities: v = v* + u. Per block, in the order assembled:
//   residual   r = G v + S l - q
//   equality   dl = -omega (G W G^T + S)^-1 r, the block solved whole
//   bounded    per row dl_i = -omega r_i / (G_i W G_i^T + S_ii), l_i clamped to [lo_i, hi_i]
//   contact    the normal row as a bounded row (l_n >= lo_n, 0 or an adhesive bound); the two
//              friction rows together by the proximal step l_t <- proj(l_t - r_t / D_max) with
//              one scale for both rows (D_max the larger diagonal: with two scales the fixed
//              point's friction would not oppose the slip), projected onto |l_t| <= mu l_n (the
//              disc for a cone bound, per row for a box bound; mu static or kinetic,
//              nmd_system.hpp); where a side is a grain, then its three turning rows
//              together, at the velocities the friction left, projected onto the ball
//              |l_roll| <= mu_r R* l_n (turning_contact_rows.hpp; a grain pair's six rows in
//              closed form, GrainPairRows)
//   then v += W G^T dl for the change actually taken.
// Warm start: l from the blocks' memory (the last solve's impulses), clamped to the bounds.
// Threads share a sweep level by level (sweep_schedule.hpp): every velocity and impulse sees the
// same operations in the same order as in a serial sweep in assembly order, for any thread count.
#include "moreau/solvers/nmd/nmd_system.hpp"
#include "moreau/solvers/nmd/sweep_schedule.hpp"

namespace moreau {

/// Starts every block from its memory (or zero without warm start) and adds their effect
/// W G^T l to the velocities.
void warm_start(NmdSystem& system, VelocitySpace& space, const NmdSettings& settings, Real h);

/// The threads a sweep of `schedule` runs on, at most `threads`: one unless its levels hold 64
/// tasks on average (below that a level's barrier costs what a second thread saves).
int sweep_threads(const SweepSchedule& schedule, int threads);
/// One sweep over the blocks in the schedule's order on up to `threads` threads (the same result
/// for any count), the equality and bounded blocks included or skipped (the direct and hybrid
/// methods factor those, solve_methods.hpp). Returns the largest impulse change.
Real gauss_seidel_sweep(NmdSystem& system, VelocitySpace& space, const NmdSettings& settings,
                        const SweepSchedule& schedule, int threads, bool equality_blocks, bool bounded_blocks);
/// settings.iterations sweeps; afterwards system.impulse holds l and space.v holds v+.
void projected_gauss_seidel(NmdSystem& system, VelocitySpace& space, const NmdSettings& settings,
                            const SweepSchedule& schedule, int threads);
/// Writes l h of each block's first memory_rows rows to its memory.
void store_impulses(const NmdSystem& system, Real h);

}  // namespace moreau
