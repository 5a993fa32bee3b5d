#pragma once
// The preconditioners a scene names ("preconditioner": "fieldsplit", ...) as PETSc options. The
// user's own options ("petsc_options") are appended after these and so override them.
#include <string>
#include <vector>

namespace moreau {

/// The names flow_petsc_options and solid_petsc_options accept.
const std::vector<std::string>& flow_petsc_preconditioners();
const std::vector<std::string>& solid_petsc_preconditioners();

/// The flow's velocity-pressure systems (nonsymmetric, equal-order with PSPG), inside
/// right-preconditioned (F)GMRES:
/// - fieldsplit: the block factorization [A Bᵀ; B C] ≈ [A Bᵀ; 0 Ŝ] ("upper"), with the Schur
///   complement S = C - B A⁻¹ Bᵀ approximated by Ŝ = C - B diag(A)⁻¹ Bᵀ ("selfp", SIMPLE's
///   approximation; Patankar & Spalding 1972) and one BoomerAMG V-cycle (hypre; Henson & Yang
///   2002, Appl. Numer. Math. 41) for A and for Ŝ. On the 3D cavity "upper" needed 5-8 % fewer
///   iterations than "lower"; the full factorization needed 11-21 % more and costs a second
///   velocity solve per iteration (30 % more time).
/// - fieldsplit_ilu: the same with ILU(0) for A instead of multigrid: cheaper per iteration, more
///   iterations as the mesh is refined. In a distributed run each rank factors its own rows of A
///   (block Jacobi), so the iterations grow with the ranks too.
/// - amg: one BoomerAMG V-cycle on the whole system (PSPG gives the pressure rows a diagonal, so
///   the saddle point is not singular on the diagonal).
/// - ilu: PETSc's ILU(0) of the whole system (of each rank's rows, block Jacobi, when distributed).
/// - lu: MUMPS's parallel sparse LU (Amestoy et al. 2001, SIAM J. Matrix Anal. Appl. 23) as a
///   direct solve.
std::string flow_petsc_options(const std::string& preconditioner, int restart);

/// The solid's tangent (symmetric; positive definite near equilibrium):
/// - amg: PETSc's smoothed-aggregation multigrid (GAMG) built on the rigid-body modes, inside CG.
/// - lu: MUMPS's sparse LU; cholesky: MUMPS's LDLᵀ (for symmetric tangents).
std::string solid_petsc_options(const std::string& preconditioner);

}  // namespace moreau
