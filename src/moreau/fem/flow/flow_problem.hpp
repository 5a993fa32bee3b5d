#pragma once
// A fluid of the FEM engine (a "fluid" in a "solver": "fem" scene): the Navier-Stokes model, how
// to advance it, and what to measure (docs/fem-scenes.md, "`fluid` (FEM)").
#include <optional>
#include <string>
#include <vector>

#include "moreau/fem/flow/navier_stokes.hpp"
#include "moreau/fem/immersed/immersed_solids.hpp"

namespace moreau {

enum class FlowProbeType {
  point, line, boundary_force, pressure_difference, kinetic_energy, newton_iterations,
  solid_point,  // an immersed solid's node: its position, displacement or velocity
  rigid_body,   // an immersed rigid body's center_of_mass, velocity, angular_velocity or torque
  solid_force,  // the fluid's force on an immersed solid or rigid body
  energy        // the fluid's kinetic energy, the solids' excess kinetic and elastic energies, their sum
};

struct FlowProbe {
  std::string name;
  FlowProbeType type = FlowProbeType::point;
  // point: its point; pressure_difference: its two points; line: its samples inside the mesh (those
  // in a gap, an obstacle cut out of the mesh, are left out), each with its cell in the fluid's mesh.
  std::vector<Vec3> sample_points;
  std::vector<MeshPoint> located;
  std::vector<Index> nodes;                 // boundary_force: the boundary's nodes
  Real coefficient_scale = 0;               // boundary_force, solid_force: 2 / (rho U^2 L) (2D) or 2 / (rho U^2 A) (3D); 0: none
  Index solid_node = -1;                    // solid_point: the node in the immersed solids' numbering
  std::string quantity;                     // solid_point: position | displacement | velocity; rigid_body: the type
  Index body = -1;                          // rigid_body: its index in immersed->rigid_bodies
  Index solid = -1;                         // solid_force: its index in immersed->model.solids
};

struct FlowProblem {
  std::string name = "fluid";  // the fluid object's name (frames/<name>_<frame>.vtu)
  NavierStokesModel model;
  FlowIntegrator integrator = FlowIntegrator::midpoint;
  FlowSolveSettings solve;
  // A time step whose solve fails is retried from its start as 2, 4, ..., 2^max_step_halvings
  // equal substeps (not with BDF2, whose formula needs equal steps).
  int max_step_halvings = 4;
  FlowLinearSettings linear;  // the linear solver inside each Newton/Picard iteration
  // Steady solves: the viscosities (Pa s) solved in turn before the model's own, each from the
  // previous solution (Reynolds-number continuation).
  std::vector<Real> continuation;
  // Their Newton tolerance: an intermediate solution only starts the next solve, so it need not be
  // converged to the final tolerance.
  Real continuation_tolerance = 1e-3;
  // "pressure_reference": {"mean": value}: the pressure is pinned at node 0 while solving and then
  // shifted so that its mean over the domain is the value.
  std::optional<Real> mean_pressure;
  VectorX initial;  // per dof: the initial velocity (and 0 pressure)
  std::vector<FlowProbe> probes;
  // Deformable solids and rigid bodies immersed in the fluid (a scene's "solid" and "rigid_body"
  // objects beside its fluid).
  std::optional<ImmersedSolids> immersed;
};

/// Column names of a probe in probes.csv (a line probe has none: it writes line_<name>.csv).
std::vector<std::string> flow_probe_columns(const FlowProbe& probe, int dim);

/// Appends a probe's values at x (the state at the end of a step of `step`, whose residual gives
/// the reactions of boundary_force); `newton_iterations` is the last step's count; `solids` the
/// immersed solids' state (null without them).
void evaluate_flow_probe(const FlowProbe& probe, const FlowProblem& problem, const VectorX& x, const FlowTimeStep& step,
                         int newton_iterations, const ImmersedSolidState* solids, std::vector<Real>& values);

/// Writes a line probe's samples as CSV: x,y[,z],velocity.x,velocity.y[,velocity.z],pressure.
void write_line_probe(const FlowProbe& probe, const FlowProblem& problem, const VectorX& x, const std::string& path);

/// The force of the fluid on a boundary from the consistent reactions: minus the sum of the
/// momentum residual over the boundary's nodes (the residual there is int N_a sigma n ds with n
/// the fluid's outward normal, plus the discrete inertia and stabilization terms). 2D: N per m.
Vec3 boundary_force(const NavierStokesModel& model, const VectorX& residual, const std::vector<Index>& nodes);

/// The mean pressure over the domain (integral of p over the measure).
Real mean_pressure(const NavierStokesModel& model, const VectorX& x);

/// The kinetic energy 1/2 rho int |u|^2 (J; 2D: J/m), exact for the Q1 field at the 2 x 2 (x 2)
/// Gauss points.
Real flow_kinetic_energy(const NavierStokesModel& model, const VectorX& x);

/// Vorticity at the nodes: the curl of the velocity averaged over the cells around each node
/// (2D: the z component in every entry's z).
std::vector<Vec3> nodal_vorticity(const NavierStokesModel& model, const VectorX& x);

}  // namespace moreau
