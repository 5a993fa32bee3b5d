#pragma once
// Checking a scene's PETSc options before its run. PETSc reads the options of the outer solver and
// preconditioner when the solver is made, but those of inner solvers (a field split's blocks, the
// sub-solvers of block Jacobi, multigrid levels) only when the preconditioner is first built or
// applied. So the check builds one and solves with it, on a small system of the kind the scene
// will solve.
#include <string>
#include <vector>

#include "moreau/fem/petsc/petsc_plugin_api.hpp"

namespace moreau {

/// The unknowns a scene's solver will meet: a flow's (three velocity components and a pressure
/// per node, for the field split) or a solid's (three displacement components per node, for the
/// rigid-body modes).
enum class PetscSystemKind { flow, solid };

struct PetscOptionCheck {
  std::string failure;               // empty if PETSc built the preconditioner
  std::vector<std::string> unused;   // options PETSc did not read ("-fieldsplit_u_pc_typ")
};

/// Makes a solver with `options`, sets up its preconditioner and solves once on a 6 x 6 x 6 grid of
/// nodes with the unknowns of `kind`, coupled like a graph Laplacian plus the identity (symmetric
/// positive definite, so every preset accepts it). Options that print (-ksp_monitor, -ksp_view)
/// print for this solve too.
PetscOptionCheck check_petsc_options(petsc_plugin::Backend& backend, const std::string& options, PetscSystemKind kind);

}  // namespace moreau
