#include "moreau/fem/scene/fem_problem.hpp"

#include <algorithm>

#include "moreau/fem/bodies/coupled_step.hpp"
#include "moreau/fem/solids/fem_assembly.hpp"

namespace moreau {

std::vector<std::string> fem_probe_columns(const FemProbe& p, int dim) {
  static const char* axes[] = {".x", ".y", ".z"};
  static const char* body_axes[] = {".d1", ".d2", ".d3"};
  std::vector<std::string> columns;
  switch (p.type) {
    case FemProbeType::displacement:
    case FemProbeType::position:
    case FemProbeType::velocity:
      for (int k = 0; k < dim; ++k) columns.push_back(p.name + axes[k]);
      break;
    case FemProbeType::body:
      for (int k = 0; k < 3; ++k) columns.push_back(p.name + (p.quantity == "body_angular_velocity" ? body_axes[k] : axes[k]));
      break;
    case FemProbeType::momentum:
      if (p.quantity == "angular" && dim == 2) {
        columns.push_back(p.name + ".z");
      } else {
        for (int k = 0; k < 3; ++k) columns.push_back(p.name + axes[k]);
      }
      break;
    case FemProbeType::energy:
    case FemProbeType::constraint_error:
    case FemProbeType::newton_iterations: columns.push_back(p.name); break;
  }
  return columns;
}

void evaluate_fem_probe(const FemProbe& p, const FemProblem& problem, const FemRunState& run, int newton_iterations,
                        std::vector<Real>& values) {
  const FemModel& model = problem.model;
  const FemDynamicState& state = run.solids;
  const int dim = model.dim;
  switch (p.type) {
    case FemProbeType::displacement:
    case FemProbeType::position:
    case FemProbeType::velocity: {
      const VectorX& field = p.type == FemProbeType::velocity ? state.v : state.u;
      const Vec3 X = model.reference_position(p.node);
      for (int k = 0; k < dim; ++k)
        values.push_back(field[model.dof(p.node, k)] + (p.type == FemProbeType::position ? X[k] : 0));
      break;
    }
    case FemProbeType::energy: {
      Real kinetic = kinetic_energy(model, state.v), potential = 0;
      // Gravity's potential -sum m_a g . x_a, with the solids' node masses the consistent mass's
      // row sums (the integrals of rho N_a).
      if (problem.gravity.squaredNorm() > 0)
        for (Index n = 0; n < model.node_count; ++n)
          for (int k = 0; k < dim; ++k)
            potential -= model.node_mass[n] * problem.gravity[k] * (model.reference_position(n)[k] + state.u[model.dof(n, k)]);
      for (size_t b = 0; b < run.bodies.size(); ++b) {
        kinetic += kinetic_energy(problem.rigid_bodies[b].body, run.bodies[b]);
        potential -= problem.rigid_bodies[b].body.mass * problem.gravity.dot(run.bodies[b].phi);
      }
      values.push_back(p.quantity == "kinetic"     ? kinetic
                       : p.quantity == "elastic"   ? state.energy
                       : p.quantity == "potential" ? potential
                                                   : kinetic + state.energy + potential);
      break;
    }
    case FemProbeType::momentum: {
      Vec3 linear, angular;
      momenta(model, state.u, state.v, linear, angular);
      for (size_t b = 0; b < run.bodies.size(); ++b) {
        linear += problem.rigid_bodies[b].body.mass * run.bodies[b].v_phi;
        angular += angular_momentum(problem.rigid_bodies[b].body, run.bodies[b]);
      }
      if (p.quantity == "angular" && dim == 2) {
        values.push_back(angular.z());
      } else {
        const Vec3& m = p.quantity == "angular" ? angular : linear;
        values.insert(values.end(), {m.x(), m.y(), m.z()});
      }
      break;
    }
    case FemProbeType::body: {
      const DirectorState& b = run.bodies[p.body];
      Vec3 v = p.quantity == "position" ? b.phi : p.quantity == "velocity" ? b.v_phi : angular_velocity(b);
      if (p.quantity == "body_angular_velocity") v = Vec3(v.dot(b.d[0]), v.dot(b.d[1]), v.dot(b.d[2]));
      values.insert(values.end(), {v.x(), v.y(), v.z()});
      break;
    }
    case FemProbeType::constraint_error: {
      Real worst = 0;
      for (const DirectorState& b : run.bodies) worst = std::max(worst, director_constraint_error(b));
      for (const FemJoint& j : problem.joints) worst = std::max(worst, joint_violation(problem, run, j));
      values.push_back(worst);
      break;
    }
    case FemProbeType::newton_iterations: values.push_back(newton_iterations); break;
  }
}

}  // namespace moreau
