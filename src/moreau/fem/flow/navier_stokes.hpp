#pragma once
// Incompressible Navier-Stokes on equal-order Q1Q1 elements (quad4 in 2D, hex8 in 3D) stabilized
// by SUPG, PSPG and LSIC (Tezduyar 1992; Tezduyar & Osawa 2000). Find (u, p)
// with, for all (w, q),
//   int w . rho (du/dt + (grad u) u - f) + int eps(w) : sigma(u, p) + int q div u
//   + sum_e int [tau (u . grad w) + tau/rho grad q] . r_M + sum_e int nu_LSIC rho div w div u = 0,
//   sigma = -p I + 2 mu eps(u),   r_M = rho (du/dt + (grad u) u - f) + grad p
// (the viscous second derivatives of r_M vanish on affine cells and are dropped, as usual for Q1).
// Stabilization parameters at each quadrature point (Tezduyar & Osawa 2000, with r = 2):
//   tau = (tau1^-2 + tau2^-2 + tau3^-2)^-1/2,  tau1 = h_UGN / (2|u|) = 1 / sum_a |u . grad N_a|,
//   tau2 = dt / 2 (transient only),  tau3 = h^2 / (4 nu) with h the cell's size (area^(1/2),
//   volume^(1/3)),  tau_PSPG = tau_SUPG = tau,  nu_LSIC = tau |u|^2.
// Newton's method with tau frozen at the current iterate (every other dependence on u, including
// the SUPG test function's, is linearised exactly); Picard (advecting velocity frozen too) as the
// fallback when Newton fails. Outflow boundaries without conditions are "do nothing"
// (sigma n = 0 in the symmetric-gradient form).
// Time stepping (FlowIntegrator): du/dt ~ (a0 u_{n+1} + a1 u_n + a2 u_{n-1}) / dt, and the
// momentum terms (convection, viscosity, SUPG) at u_theta = theta u_{n+1} + (1 - theta) u_n:
//   backward Euler a = (1, -1, 0), theta = 1;    BDF2 a = (3/2, -2, 1/2), theta = 1;
//   midpoint (Crank-Nicolson) a = (1, -1, 0), theta = 1/2.
// The whole system, continuity and PSPG included, is evaluated at n + theta: with the midpoint
// rule the pressure unknown is the pressure at t_{n+1/2} (the multiplier of the midpoint momentum
// balance), and the PSPG-modified continuity holds at t_{n+1/2} too. (Continuity at n+1 with the
// PSPG residual at n+1/2 mixes time levels in one equation and was measured first order.)
#include <functional>
#include <memory>
#include <vector>

#include "moreau/fem/core/fem_mesh.hpp"
#include "moreau/fem/core/mesh_locator.hpp"
#include "moreau/fem/distributed/row_ownership.hpp"
#include "moreau/fem/solids/fem_model.hpp"
#include "moreau/fem/flow/flow_linear_solver.hpp"
#include "moreau/fem/solids/static_solver.hpp"

namespace moreau {

enum class FlowIntegrator { steady, backward_euler, bdf2, midpoint };

/// One step of a flow integrator: the scheme, dt and the previous states it needs.
struct FlowTimeStep {
  FlowIntegrator integrator = FlowIntegrator::steady;
  Real dt = 0;                               // s; ignored when steady
  const VectorX* previous = nullptr;         // x_n (every transient scheme)
  const VectorX* before_previous = nullptr;  // x_{n-1} (BDF2)
  bool transient() const { return integrator != FlowIntegrator::steady; }
};

/// The nonlinear solve's settings: Newton, then (if it fails) Picard from the same start until the
/// residual has dropped by picard_reduction, then Newton again.
struct FlowSolveSettings {
  Real tolerance = 1e-8;        // relative to the first residual, or to |x| for the correction
  int max_iterations = 25;      // Newton iterations per attempt
  bool picard_fallback = true;
  int max_picard_iterations = 100;
  Real picard_reduction = 1e-3;
  Real viscosity = 0;           // Pa s of this solve; 0: the model's (continuation stages solve at their own)
  int threads = 0;              // worker threads of the assembly (0 = all cores); results do not depend on it
};

/// How one assembly evaluates the equations.
struct FlowAssembly {
  bool picard = false;  // the advecting velocity frozen too (Picard's Jacobian)
  bool own_rows_only = false;  // a distributed run: only this rank's cells (R and J right in its rows only)
  Real viscosity = 0;   // Pa s; 0: the model's
  int threads = 0;      // 0: all cores
};

/// This rank's share of a distributed flow: the rows it owns and the cells it assembles (every cell
/// with a node of its own, so that its rows receive all their terms).
struct FlowPartition {
  RowOwnership rows;
  std::vector<std::vector<Index>> colours;  // this rank's cells, in the model's colours
  Index cells = 0;
};

struct NavierStokesModel {
  FemMesh mesh;                  // quad4 or hex8
  Real density = 1;              // kg/m^3
  Real viscosity = 0.01;         // dynamic, Pa s
  Vec3 body_force = Vec3::Zero();  // per unit mass, m/s^2
  // For tests of the Jacobian only: if > 0, tau and nu_LSIC take these values everywhere (the
  // Jacobian treats them as constants, so with them fixed it is the exact derivative).
  Real fixed_tau = 0, fixed_lsic = 0;
  // Per node: dim velocity components, then the pressure.
  std::vector<PrescribedDof> prescribed;
  // Built by setup_navier_stokes:
  int points = 0;
  std::vector<Real> weight, shape;   // [cell][point], [cell][point][node]
  std::vector<Vec3> gradient;        // [cell][point][node]
  std::vector<Real> cell_size;       // m
  std::vector<Real> node_volume;     // per node, the integral of its shape function, m^3 (2D: m^2)
  std::vector<std::vector<Index>> colours;
  std::vector<Index> free_index, slots;
  Index free_count = 0;
  SparseMatrix pattern;  // distributed: this rank's rows only
  std::shared_ptr<const FlowPartition> partition;  // null on one process

  int dim() const { return mesh.dim; }
  int fields() const { return mesh.dim + 1; }
  Index dof_count() const { return mesh.node_count() * fields(); }
  Index dof(Index node, int field) const { return node * fields() + field; }
};

/// Quadrature, colours, the free dofs and the Jacobian's sparsity; after `prescribed` is set.
/// With `ranks` of more than one process (a distributed run, solved by PETSc): the mesh's nodes
/// divided among them (METIS), and `partition` and `pattern` made this rank's.
void setup_navier_stokes(NavierStokesModel& model, const petsc_plugin::Communicator* ranks = nullptr);

/// A force density on the fluid beyond its cells' own (a source's, N/m^3): `values` per dof, at
/// the velocity dofs of each node (pressure entries unused), interpolated by the shape functions.
/// The stabilization's strong residual includes it. If `jacobian` is given too, the assembly
/// writes there the residual's derivative in `values` (free rows and, as the values are zero on
/// prescribed dofs, free columns).
struct FlowForceDensity {
  const VectorX* values = nullptr;
  SparseMatrix* jacobian = nullptr;
};

/// The residual on all dofs at x (the state at t_{n+1}) and, if `J` is given, its Jacobian (tau
/// frozen; `how.picard`: the advecting velocity frozen too) on the free dofs. Cells in parallel by
/// colours, deterministic.
void assemble_flow(const NavierStokesModel& model, const VectorX& x, const FlowTimeStep& step, VectorX& R,
                   SparseMatrix* J, const FlowAssembly& how = {}, const FlowForceDensity& density = {});

/// Terms of the momentum balance beyond the fluid's cells that depend on the whole state, such as
/// an immersed solid (fem/immersed). They are added to the cells' (Galerkin) residual and Jacobian
/// in every evaluation, and their force density (the residual per node over the node's lumped
/// volume) joins the stabilization's strong residual (flow_source_assembly.hpp).
/// A low-rank part of a source's Jacobian on the free dofs, J += U V^T (U, V: free dofs x rank).
/// Kept out of the sparse matrix, where it would fill a dense block, and applied in the linear
/// solve by the Sherman-Morrison-Woodbury identity:
///   (A + U V^T)^-1 b = A^-1 b - Z (I + V^T Z)^-1 V^T A^-1 b,   Z = A^-1 U (rank more solves).
struct FlowLowRank {
  Eigen::MatrixXd U, V;
};

class FlowSource {
 public:
  virtual ~FlowSource() = default;
  /// Adds the source's residual at x (the state at t_{n+1} of `step`) to R (all dofs) and, if
  /// `jacobian` is given, its Jacobian entries on the free dofs as triplets (free row, free column).
  /// If `low_rank` is given too, the source may put a low-rank part of its Jacobian there instead
  /// of in the triplets (appending columns to U and V); without it the triplets hold the whole.
  virtual void add(const VectorX& x, const FlowTimeStep& step, VectorX& R, std::vector<Eigen::Triplet<Real, int>>* jacobian,
                   FlowLowRank* low_rank = nullptr) const = 0;
  /// A step of `step` has converged at x: the source advances its own state to t_{n+1}.
  virtual void accept(const VectorX& x, const FlowTimeStep& step) = 0;
  /// Why the last add() made the residual not finite (a solid's node left the fluid's mesh), or
  /// empty if it did not or the source cannot tell.
  virtual std::string last_failure() const { return {}; }
};

struct FlowSolveResult : NewtonResult {
  int picard_iterations = 0;
  double source_s = 0;  // wall time in the source's terms (included in assembly_s)
};

/// Solves one step (or the steady equations) starting from x, whose prescribed dofs are first set
/// to their values at t. Converged when |R| <= tolerance * |R_0| or the correction is below
/// tolerance * |x|.
/// `source`, if given, adds its terms to every evaluation (it is not told of the result: the caller
/// accepts a converged step).
FlowSolveResult solve_navier_stokes(const NavierStokesModel& model, Real t, const FlowTimeStep& step, VectorX& x,
                                    FlowLinearSolver& solver, const FlowSolveSettings& settings = {},
                                    const FlowSource* source = nullptr);

/// Velocity and pressure at a point of the fluid's mesh (found by MeshLocator::locate on
/// model.mesh): sum_a N_a(x) x_a over the point's cell.
void interpolate_flow(const NavierStokesModel& model, const MeshPoint& at, const VectorX& x, Vec3& velocity, Real& pressure);
/// One field at such a point: velocity component k < dim, or the pressure at k = dim.
Real interpolate_flow_component(const NavierStokesModel& model, const MeshPoint& at, const VectorX& x, int k);

}  // namespace moreau
