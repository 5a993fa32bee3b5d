#include "moreau/fem/fem_problem.hpp"

namespace moreau {

std::vector<std::string> fem_probe_columns(const FemProbe& p, int dim) {
  static const char* axes[] = {".x", ".y", ".z"};
  std::vector<std::string> columns;
  switch (p.type) {
    case FemProbeType::displacement:
    case FemProbeType::position:
    case FemProbeType::velocity:
      for (int k = 0; k < dim; ++k) columns.push_back(p.name + axes[k]);
      break;
    case FemProbeType::momentum:
      if (p.quantity == "angular" && dim == 2) {
        columns.push_back(p.name + ".z");
      } else {
        for (int k = 0; k < 3; ++k) columns.push_back(p.name + axes[k]);
      }
      break;
    case FemProbeType::energy:
    case FemProbeType::newton_iterations: columns.push_back(p.name); break;
  }
  return columns;
}

void evaluate_fem_probe(const FemProbe& p, const FemModel& model, const FemDynamicState& state, int newton_iterations,
                        std::vector<Real>& values) {
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
      const Real kinetic = kinetic_energy(model, state.v);
      values.push_back(p.quantity == "kinetic" ? kinetic : p.quantity == "strain" ? state.energy : kinetic + state.energy);
      break;
    }
    case FemProbeType::momentum: {
      Vec3 linear, angular;
      momenta(model, state.u, state.v, linear, angular);
      if (p.quantity == "angular" && dim == 2) {
        values.push_back(angular.z());
      } else {
        const Vec3& m = p.quantity == "angular" ? angular : linear;
        values.insert(values.end(), {m.x(), m.y(), m.z()});
      }
      break;
    }
    case FemProbeType::newton_iterations: values.push_back(newton_iterations); break;
  }
}

}  // namespace moreau
