#pragma once
// Reading "solver": "fem" scenes: solids, rigid bodies and joints (build_fem.cpp), a fluid
// (build_flow.cpp) and what both read alike (build_fem_common.cpp).
#include <memory>
#include <string>
#include <vector>

#include "moreau/fem/petsc/petsc_option_check.hpp"
#include "moreau/fem/scene/fem_problem.hpp"
#include "moreau/math/expression.hpp"
#include "moreau/scene/json_reader.hpp"

namespace moreau {

/// Marks the FEM keys of "settings" (integrator, newton) as known; build_fem_scene reads them.
void allow_fem_settings(const JsonObject& settings);

/// The "objects" (solids and rigid bodies, or one fluid), "joints" and "probes", and the FEM
/// settings; gravity (m/s^2) becomes a body load on every solid and fluid and a force m g on
/// every rigid body.
void build_fem_scene(const JsonObject& top, FemProblem& problem, const Vec3& gravity, int threads);

/// The fluid object of a FEM scene and the solids and rigid bodies immersed in it (settings: the
/// scene's "settings", if any).
void build_flow_scene(const JsonObject& top, const JsonObject& fluid, const std::vector<JsonObject>& solids,
                      const std::vector<JsonObject>& rigid_bodies, const JsonObject* settings, FemProblem& problem,
                      const Vec3& gravity, int threads);

/// The "solid" and "rigid_body" objects of a scene with a fluid: deformable solids and rigid bodies
/// immersed in it (build_immersed.cpp); dt is the scene's step (s).
void read_immersed_solids(const JsonObject& top, const std::vector<JsonObject>& solids,
                          const std::vector<JsonObject>& rigid_bodies, Real dt, FlowProblem& problem);

// --- shared readers ---

/// Loads the PETSc plugin for `"type": "petsc"` in `linear_solver` and has PETSc build a
/// preconditioner with the options of each of the scene's solvers (the preset's and the user's)
/// on a small system of `kind` (petsc_option_check.hpp); fails naming linear_solver.type, with
/// where the plugin was looked for, if it cannot be loaded, or naming petsc_options if PETSc
/// rejects them. Returns a warning for the user's options that no solver read, or "".
std::string require_petsc(const JsonObject& linear_solver, const std::vector<std::string>& solvers_options,
                          PetscSystemKind kind);
/// In a distributed run (more than one MPI rank) the FEM systems are solved by PETSc: fails at
/// settings.linear_solver.type unless `uses_petsc`.
void require_petsc_when_distributed(const JsonObject& top, const JsonObject* settings, bool uses_petsc);

/// A solid's "material": a hyperelastic model with Young's modulus and Poisson's ratio or Lame's
/// parameters, and its density.
HyperelasticMaterial read_fem_material(const JsonObject& material);
/// A solid object's "formulation" ("displacement" or "mean_dilatation"), checked against its
/// material and cells (mean dilatation: Neo-Hookean on quad4/hex8).
VolumeTreatment read_volume_treatment(const JsonObject& solid_json, const FemSolid& solid);

/// A solid's "dirichlet" list: prescribed displacement components of the nodes a "where" selects.
void read_dirichlet(const JsonObject& solid_json, FemModel& model, Index solid);

/// A point of `dim` numbers (z = 0 in 2D).
Vec3 read_point(const JsonObject& j, const std::string& key, int dim);

/// A mesh: "rectangle" / "box" (with optional "grading" and "remove"), "msh" (Gmsh MSH 4.1) or
/// "geo" (meshed by Gmsh); cells are oriented and validated (`where` names it in errors).
/// What a mesh is for: its memory per cell differs (a flow has more unknowns per node, and LU factors).
enum class MeshUse { solid, flow };
FemMesh read_fem_mesh(const JsonObject& mesh, const std::string& where, MeshUse use);

/// One expression of t, x, y, z per component: a number, a string, or (if `allow_null`) null.
std::vector<std::unique_ptr<Expression>> read_components(const JsonObject& j, const std::string& key, int dim,
                                                         bool allow_null);

/// The nodes a "where" selects: {"boundary" | "side" | "tag": name or [names]} or {"box": {"min",
/// "max"}}; sorted, unique. `boundary_name` is set when exactly one boundary is named.
std::vector<Index> select_nodes(const JsonObject& where, const FemMesh& mesh, std::string* boundary_name);

}  // namespace moreau
