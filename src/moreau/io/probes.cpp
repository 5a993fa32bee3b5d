#include "moreau/io/probes.hpp"

#include <limits>

namespace moreau {

bool ProbeSpec::is_vector() const {
  switch (type) {
    case ProbeType::point:
    case ProbeType::center_of_mass:
    case ProbeType::momentum:
      return true;
    default:
      return false;
  }
}

std::vector<std::string> probe_columns(const ProbeSpec& probe) {
  if (!probe.is_vector()) return {probe.name};
  return {probe.name + ".x", probe.name + ".y", probe.name + ".z"};
}

void evaluate_probe(const ProbeSpec& probe, const Model& model, const State& state, std::vector<Real>& values) {
  auto push3 = [&](const Vec3& v) { values.insert(values.end(), {v.x(), v.y(), v.z()}); };
  switch (probe.type) {
    case ProbeType::point: {
      const Index p = probe.particle;
      if (probe.quantity == "position") push3(state.position[p]);
      else if (probe.quantity == "displacement") push3(state.position[p] - model.particle_rest_position[p]);
      else push3(state.velocity[p]);
      break;
    }
    case ProbeType::energy: {
      Real e = 0;
      if (probe.quantity == "kinetic" || probe.quantity == "total") e += kinetic_energy(model, state, probe.object);
      if (probe.quantity == "potential" || probe.quantity == "total") e += potential_energy(model, state, probe.object);
      if (probe.quantity == "elastic" || probe.quantity == "total") e += elastic_energy(model, state, probe.object);
      values.push_back(e);
      break;
    }
    case ProbeType::center_of_mass:
      push3(center_of_mass(model, state, probe.object));
      break;
    case ProbeType::extent: {
      const bool want_max = probe.quantity == "max";
      Real e = want_max ? -std::numeric_limits<Real>::infinity() : std::numeric_limits<Real>::infinity();
      const Index begin = probe.object >= 0 ? model.objects[probe.object].particle_begin : 0;
      const Index end = probe.object >= 0 ? model.objects[probe.object].particle_end : model.particle_count();
      for (Index p = begin; p < end; ++p)
        e = want_max ? std::max(e, state.position[p][probe.axis]) : std::min(e, state.position[p][probe.axis]);
      values.push_back(e);
      break;
    }
    case ProbeType::momentum:
      push3(probe.quantity == "linear" ? linear_momentum(model, state, probe.object)
                                       : angular_momentum(model, state, probe.object, probe.about));
      break;
    case ProbeType::constraint_error:
      values.push_back(max_constraint_error(model, state, probe.object, probe.family));
      break;
  }
}

}  // namespace moreau
