#pragma once
// What a step changes about the fluids and what the next step, a probe or the output reads; the
// step's per-iteration buffers are the solver's (fluid_scratch.hpp). Arrays hold `capacity`
// entries; the first `count` are live.
// Whenever the neighbour lists are rebuilt, the live particles are re-sorted along the z-order
// curve of the neighbour grid (every per-particle array moves together; `id` keeps each
// particle's original number for output).
#include <vector>

#include "moreau/fluids/fluid_model.hpp"
#include "moreau/geometry/cell_grid.hpp"

namespace moreau {

/// Neighbour lists with a fixed row length per particle: row i holds count[i] entries starting at
/// i * stride (at most stride - 1: the last slot is the fill's spare). Rows are written by their
/// own particle only (parallel, deterministic, no prefix sum). The stride is a whole number of pair
/// chunks (pair_chunks.hpp), and a row's entries past count[i] up to its last whole chunk repeat
/// its first entry, so a chunk of indices is always valid to load.
struct FixedStrideLists {
  Index stride = 0;
  std::vector<Index> count;
  std::vector<Index> entries;

  const Index* row(Index i) const { return entries.data() + static_cast<std::size_t>(i) * stride; }
};

/// The implicit viscosity solver's work over a run (fluid_viscosity.hpp).
struct ViscositySolveStats {
  long solves = 0;              // implicit solves (one per substep under XPBD, per step under nmd)
  long iterations = 0;          // BiCGSTAB iterations, summed
  int most_iterations = 0;      // in one solve
  long unconverged = 0;         // solves that stopped at the iteration limit
  Real worst_residual = 0;      // largest relative residual a solve stopped at
};

struct FluidState {
  Index count = 0;
  std::vector<Vec3> position, velocity;  // m, m/s
  std::vector<Vec3> listed_position;     // m, positions when the lists were built
  std::vector<Index> phase, id;
  Index next_id = 0;                     // id of the next emitted particle
  std::vector<Index> emitted_layers;     // per emitter: layers released so far
  std::vector<Real> inv_mass, mass;      // 1/kg, kg (the phase's; inverse mass 0 while solid or held in a nozzle)
  std::vector<Real> pressure;            // Pa, -sum over the substep's iterations of lambda / (V h^2)
  std::vector<Real> density;             // kg/m^3 at the last evaluation
  std::vector<Real> enthalpy;            // J/kg, specific (fluid_heat.hpp; unused unless the model is thermal)
  std::vector<Real> viscosity;           // m^2/s, kinematic: the phase's, or its state's (fluid_heat.hpp)
  std::vector<Real> smoke;               // a gas's marker concentration, 1 as released (ambient_air.hpp; 0 for liquids)
  std::vector<Real> release_time;        // s, when a particle held in its emitter's nozzle goes free; 0: free

  // Collider wall samples in world space at the time of the current substep.
  std::vector<Vec3> boundary_position;
  // Cloth, soft-body and rigid-body samples in world space (from the solids' current positions,
  // solid_coupling.hpp).
  std::vector<Vec3> solid_position;

  // Neighbour search.
  GridFrame frame;
  CellGrid fluid_grid, boundary_grid, solid_grid;
  bool boundary_grid_built = false;
  FixedStrideLists fluid_neighbors;     // fluid j of fluid i, |x_i - x_j| < h + skin at the build
  FixedStrideLists boundary_neighbors;  // wall sample b of fluid i
  FixedStrideLists solid_neighbors;     // solid sample s of fluid i
  FixedStrideLists solid_fluids;        // fluid i of solid sample s (the reverse lists, for the reaction)
  bool lists_stale = true;              // forces a rebuild (start, emitted particles)
  bool rebuilding = false;              // shared decision of the current update
  Real listed_time = 0;                 // s, time of the last build
  long list_builds = 0;

  // Time-step monitor.
  Real max_cfl = 0;                     // max over the run of max|v| h_sub / (2 r)
  long cfl_violations = 0;              // steps whose CFL number exceeded the limit
  ViscositySolveStats viscosity_stats;
};

/// Sizes every buffer for the model's capacity and places the initial particles.
FluidState make_fluid_state(const FluidModel& fluid);

}  // namespace moreau
