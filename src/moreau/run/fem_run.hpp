#pragma once
// The run loop of "solver": "fem" scenes behind moreau::Simulation (simulation.cpp dispatches).
#include <string>

#include "moreau/moreau.hpp"
#include "moreau/scene/scene.hpp"

namespace moreau {

/// Steps the FEM problem to the duration (static: load steps at t = dt, 2 dt, ...; dynamic: the
/// midpoint rule or the energy-momentum scheme), writing probes.csv, frames and run.json like an
/// XPBD run. Throws NumericalError naming the step, time and solid if a step fails.
RunResult run_fem_scene(Scene& scene, const RunOptions& options);

/// What a FEM scene builds: solids, nodes, cells, dofs, loads, conditions.
std::string fem_summary(const Scene& scene);

/// The run loop of a FEM scene with a "fluid" (flow_run.cpp): a steady solve with viscosity
/// continuation, or time steps; exit-3 NumericalError naming the step and time on failure.
RunResult run_flow_scene(Scene& scene, const RunOptions& options);

/// What a fluid scene builds: mesh, material, unknowns.
std::string flow_summary(const Scene& scene);

}  // namespace moreau
