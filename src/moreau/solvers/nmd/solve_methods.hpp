#pragma once
// The direct and hybrid methods of an NMD solve (nmd_settings.hpp, NmdMethod); projected
// Gauss-Seidel is projected_gauss_seidel.hpp. Both factor a set of rows F in one sparse Cholesky factorisation (schur_complement.hpp),
// A_FF = G_F W G_F^T + S_F (schur_complement.hpp), and solve the remaining rows (contacts; for
// hybrid also the bounded joint rows) by projected Gauss-Seidel sweeps, alternated until no
// impulse moves by more than settings.tolerance or settings.iterations rounds have passed, ending
// with a solve of F (the split that lets a solver hold large mass ratios: Lacoursiere 2007; the
// AGX "split" solver):
//   hybrid  F = the equality blocks' rows: dl_F = -A_FF^-1 (G_F v + S_F l_F - q_F).
//   direct  F = the equality and bounded rows (joint limits and drives): with v_0 the velocities
//           without F's impulses, l_F solves the bounded problem A_FF l_F = q_F - G_F v_0 by an
//           active-set loop (block principal pivoting, Judice & Pires 1994): rows at a bound are
//           clamped there, the others solved; free rows that leave their bounds are clamped and
//           clamped rows whose w = A l - b points inwards are freed, all at once, until nothing
//           changes. The pattern of A_FF stays (clamped rows become identity rows), so its
//           symbolic analysis is reused.
// Contacts stay with projected Gauss-Seidel in both: the rows of a box resting on four corners
// repeat each other, which leaves A singular unless every contact has a compliance.
#include "moreau/solvers/nmd/nmd_system.hpp"
#include "moreau/solvers/nmd/schur_complement.hpp"
#include "moreau/solvers/nmd/sweep_schedule.hpp"

namespace moreau {

/// The sweeps run on up to `threads` threads in the schedule's order (the same result for any
/// count). Returns false when A_FF was not positive definite (the caller reports it).
bool solve_factored(NmdSystem& system, VelocitySpace& space, const NmdSettings& settings, SchurComplement& schur,
                    const SweepSchedule& schedule, int threads);

}  // namespace moreau
