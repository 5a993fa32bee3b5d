#pragma once
// Settings of the velocity-level formulation (`"solver": "nmd"`, scene key `settings.nmd`;
// docs/scene-format.md). The constraint engine's `substeps` and `iterations` are XPBD's: an NMD
// step takes its own `substeps` velocity solves of `iterations` sweeps each.
#include "moreau/math/types.hpp"

namespace moreau {

/// How the friction rows of a contact are bounded by its normal impulse: the disc
/// |lambda_t| <= mu lambda_n (isotropic), or the box |lambda_t,k| <= mu lambda_n per tangent.
enum class FrictionBound { cone, box };

/// How the system of a solve is solved (docs/scene-format.md, settings.nmd.method):
///   pgs     projected Gauss-Seidel over the blocks (projected_gauss_seidel.hpp),
///   direct  the joints' and materials' rows, limits and drives included, in one sparse Cholesky factorisation (schur_complement.hpp) with
///           an active-set loop for the bounds; contacts by projected Gauss-Seidel, alternated
///           (solve_methods.hpp),
///   hybrid  the equality rows in one sparse Cholesky factorisation (schur_complement.hpp), the rest by projected Gauss-Seidel, alternated.
enum class NmdMethod { pgs, direct, hybrid };

struct NmdSettings {
  NmdMethod method = NmdMethod::pgs;
  int substeps = 1;                 // velocity solves per dt
  int iterations = 50;              // sweeps (pgs), rounds of the alternation and active-set passes
  Real tolerance = 1e-10;           // direct, hybrid: stop when no impulse changes by more (N s)
  Real over_relaxation = 1.0;       // omega in (0, 2)
  Real stabilization = 2.0;         // d: relaxation of hard rows in steps (tau = d h); 2 is critical
  FrictionBound friction = FrictionBound::cone;
  Real restitution_threshold = 0.1; // m/s: contacts approaching slower do not bounce
  Real sliding_speed = 1e-3;        // m/s: a contact slipping faster at the step's start takes mu_k
  Real contact_compliance = 1e-7;   // m/N, normal rows of every contact
  bool warm_start = true;           // start each solve from the last step's impulses
};

}  // namespace moreau
