#pragma once
// A scene of the FEM engine ("solver": "fem"): the model, how to step it, and what to measure.
#include <optional>
#include <string>
#include <vector>

#include "moreau/fem/bodies/director_body.hpp"
#include "moreau/fem/solids/dynamic_solver.hpp"
#include "moreau/fem/bodies/fem_joints.hpp"
#include "moreau/fem/solids/fem_model.hpp"
#include "moreau/fem/flow/flow_problem.hpp"
#include "moreau/fem/solids/static_solver.hpp"

namespace moreau {

enum class FemIntegrator { static_load_steps, midpoint, energy_momentum };

enum class FemProbeType { displacement, position, velocity, energy, momentum, newton_iterations, body, constraint_error };

struct FemProbe {
  std::string name;
  FemProbeType type = FemProbeType::energy;
  Index node = -1;           // global node (displacement, position, velocity)
  Index body = -1;           // rigid body (body)
  std::string quantity;      // energy: kinetic | elastic | potential | total; momentum: linear | angular;
                             // body: position | velocity | angular_velocity
};

/// A rigid body of the FEM engine: a director frame with the mass properties of its mesh.
struct FemRigidBody {
  std::string name;
  FemMesh mesh;              // reference configuration (for the mass properties and the output)
  DirectorBody body;
  DirectorState initial;
};

/// Everything a FEM run advances: the solids' dofs and the rigid bodies' directors.
struct FemRunState {
  FemDynamicState solids;
  std::vector<DirectorState> bodies;
};

struct FemProblem {
  FemModel model;
  FemIntegrator integrator = FemIntegrator::energy_momentum;
  Real dt = 1.0 / 60;        // s, settings.dt (a flow's steady solve ignores it)
  int threads = 0;           // settings.threads: the most worker threads a step may use (0 = all cores)
  NewtonSettings newton;
  SolidLinearSettings linear;  // settings.linear_solver of a scene of solids
  VectorX initial_velocity;  // per dof
  std::vector<FemRigidBody> rigid_bodies;
  std::vector<FemJoint> joints;
  Vec3 gravity = Vec3::Zero();  // m/s^2, acts on the rigid bodies (on the solids it is a load)
  std::vector<FemProbe> probes;
  std::optional<FlowProblem> flow;  // a "fluid" scene (then no solids, bodies or joints)
};

/// Column names of a probe in probes.csv.
std::vector<std::string> fem_probe_columns(const FemProbe& probe, int dim);

/// Appends a probe's values at the current state; `newton_iterations` is the last step's count.
/// Energy and momentum probes sum the solids and the rigid bodies.
void evaluate_fem_probe(const FemProbe& probe, const FemProblem& problem, const FemRunState& state,
                        int newton_iterations, std::vector<Real>& values);

}  // namespace moreau
