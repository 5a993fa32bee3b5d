#pragma once
// A scene of the FEM engine ("solver": "fem"): the model, how to step it, and what to measure.
#include <string>
#include <vector>

#include "moreau/fem/dynamic_solver.hpp"
#include "moreau/fem/fem_model.hpp"
#include "moreau/fem/static_solver.hpp"

namespace moreau {

enum class FemIntegrator { static_load_steps, midpoint, energy_momentum };

enum class FemProbeType { displacement, position, velocity, energy, momentum, newton_iterations };

struct FemProbe {
  std::string name;
  FemProbeType type = FemProbeType::energy;
  Index node = -1;           // global node (displacement, position, velocity)
  std::string quantity;      // energy: kinetic | strain | total; momentum: linear | angular
};

struct FemProblem {
  FemModel model;
  FemIntegrator integrator = FemIntegrator::energy_momentum;
  NewtonSettings newton;
  VectorX initial_velocity;  // per dof
  std::vector<FemProbe> probes;
};

/// Column names of a probe in probes.csv.
std::vector<std::string> fem_probe_columns(const FemProbe& probe, int dim);

/// Appends a probe's values at the current state; `newton_iterations` is the last step's count.
void evaluate_fem_probe(const FemProbe& probe, const FemModel& model, const FemDynamicState& state,
                        int newton_iterations, std::vector<Real>& values);

}  // namespace moreau
