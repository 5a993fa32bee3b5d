#include "moreau/fem/petsc/petsc_presets.hpp"

#include <fmt/format.h>

namespace moreau {

const std::vector<std::string>& flow_petsc_preconditioners() {
  static const std::vector<std::string> names = {"fieldsplit", "amg", "ilu", "lu"};
  return names;
}

const std::vector<std::string>& solid_petsc_preconditioners() {
  static const std::vector<std::string> names = {"amg", "lu", "cholesky"};
  return names;
}

std::string flow_petsc_options(const std::string& preconditioner, int restart) {
  const std::string krylov = fmt::format("-ksp_gmres_restart {} -ksp_pc_side right ", restart);
  if (preconditioner == "fieldsplit")
    return "-ksp_type fgmres " + krylov +
           "-pc_type fieldsplit -pc_fieldsplit_type schur -pc_fieldsplit_schur_fact_type lower "
           "-pc_fieldsplit_schur_precondition selfp "
           "-fieldsplit_u_ksp_type preonly -fieldsplit_u_pc_type hypre -fieldsplit_u_pc_hypre_type boomeramg "
           "-fieldsplit_p_ksp_type preonly -fieldsplit_p_pc_type hypre -fieldsplit_p_pc_hypre_type boomeramg";
  if (preconditioner == "amg") return "-ksp_type gmres " + krylov + "-pc_type hypre -pc_hypre_type boomeramg";
  if (preconditioner == "ilu") return "-ksp_type gmres " + krylov + "-pc_type ilu";
  return "-ksp_type preonly -pc_type lu -pc_factor_mat_solver_type mumps";
}

std::string solid_petsc_options(const std::string& preconditioner) {
  if (preconditioner == "amg") return "-ksp_type cg -pc_type gamg";
  if (preconditioner == "cholesky") return "-ksp_type preonly -pc_type cholesky -pc_factor_mat_solver_type mumps";
  return "-ksp_type preonly -pc_type lu -pc_factor_mat_solver_type mumps";
}

}  // namespace moreau
