#include "moreau/io/probes.hpp"

#include <cmath>
#include <algorithm>
#include <limits>

#include "moreau/collision/penetration.hpp"
#include "moreau/fluids/fluid_heat.hpp"
#include "moreau/io/granular_probes.hpp"
#include "moreau/rods/rod_geometry.hpp"

namespace moreau {

bool Probe::is_vector() const {
  switch (type) {
    case ProbeType::point:
    case ProbeType::rod_point:
    case ProbeType::center_of_mass:
    case ProbeType::momentum:
    case ProbeType::body_position:
    case ProbeType::body_velocity:
    case ProbeType::body_angular_velocity:
      return true;
    default:
      return false;
  }
}

int Probe::width() const {
  if (type == ProbeType::body_orientation) return 4;
  if (type == ProbeType::joint_error) return 2;
  if (type == ProbeType::suction) return 4;
  return is_vector() ? 3 : 1;
}

std::vector<std::string> probe_columns(const Probe& probe) {
  if (probe.type == ProbeType::body_orientation)
    return {probe.name + ".w", probe.name + ".x", probe.name + ".y", probe.name + ".z"};
  if (probe.type == ProbeType::joint_error) return {probe.name + ".position", probe.name + ".angle"};
  if (probe.type == ProbeType::suction)
    return {probe.name + ".sealed", probe.name + ".pressure_difference", probe.name + ".volume", probe.name + ".area"};
  if (!probe.is_vector()) return {probe.name};
  return {probe.name + ".x", probe.name + ".y", probe.name + ".z"};
}

namespace {

// Positions of the object's particles (fluid or not), or of every simulated particle (-1).
template <class F>
void for_each_position(const Model& model, const State& state, Index object, F&& f) {
  for_each_live_particle(model, state, object, [&](Index p) { f(state.position[p]); });
  for_each_fluid_particle(model, state, object, [&](Index i) { f(state.fluid.position[i]); });
}

}  // namespace

void evaluate_probe(const Probe& probe, const Model& model, const State& state, std::vector<Real>& values) {
  auto push3 = [&](const Vec3& v) { values.insert(values.end(), {v.x(), v.y(), v.z()}); };
  switch (probe.type) {
    case ProbeType::point: {
      const Index p = probe.particle;
      if (probe.quantity == "position") push3(state.position[p]);
      else if (probe.quantity == "displacement") push3(state.position[p] - model.particle_rest_position[p]);
      else push3(state.velocity[p]);
      break;
    }
    case ProbeType::rod_point: {
      const RodModel& rod = model.rods[probe.rod];
      if (probe.quantity == "velocity") push3(rod_point_velocity(rod, state.rigid, probe.rod_point));
      else if (probe.quantity == "displacement") push3(rod_point(rod, state.rigid, probe.rod_point) - rod.rest_points[probe.rod_point]);
      else push3(rod_point(rod, state.rigid, probe.rod_point));
      break;
    }
    case ProbeType::rod_twist:
      values.push_back(rod_twist(model.rods[probe.rod], model.joints, state));
      break;
    case ProbeType::angle_of_repose:
      values.push_back(angle_of_repose(model, state, probe.object, probe.pile_axis, probe.ring_width, probe.pile_region,
                                        probe.resting_speed));
      break;
    case ProbeType::runout:
      values.push_back(runout(model, state, probe.object, probe.pile_axis, probe.runout_direction, probe.runout_fraction));
      break;
    case ProbeType::mass_flow:
      values.push_back(probe.quantity == "beyond"
                           ? mass_beyond(model, state, probe.object, probe.plane_point, probe.plane_normal)
                           : mass_flow_rate(model, state, probe.object, probe.plane_point, probe.plane_normal));
      break;
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
      bool any = false;
      for_each_position(model, state, probe.object, [&](const Vec3& x) {
        e = want_max ? std::max(e, x[probe.axis]) : std::min(e, x[probe.axis]);
        any = true;
      });
      values.push_back(any ? e : std::numeric_limits<Real>::quiet_NaN());  // no particle yet (an emitter): no extent
      break;
    }
    case ProbeType::fluid_height: {
      // Highest particle top (y + r along -g) within 2r of the vertical line through `at`;
      // measured from the point `at` itself along the up direction. 0 where no particle is.
      const Vec3 up = model.settings.gravity.norm() > 0 ? Vec3(-model.settings.gravity.normalized()) : Vec3::UnitY();
      const Real r = model.fluid.particle_radius, reach2 = 4 * r * r;
      Real top = 0;
      for_each_fluid_particle(model, state, probe.object, [&](Index i) {
        const Vec3 d = state.fluid.position[i] - probe.at;
        const Real height = d.dot(up);
        if ((d - height * up).squaredNorm() <= reach2) top = std::max(top, height + r);
      });
      values.push_back(top);
      break;
    }
    case ProbeType::density_error: {
      // Compression error max(rho_i / rho0 - 1, 0) at the last density evaluation: its mean or max.
      Real sum = 0, worst = 0;
      Index count = 0;
      for_each_fluid_particle(model, state, probe.object, [&](Index i) {
        const Real rho0 = model.fluid.phases[state.fluid.phase[i]].rest_density;
        const Real e = std::max(state.fluid.density[i] / rho0 - 1, 0.0);
        sum += e;
        worst = std::max(worst, e);
        ++count;
      });
      values.push_back(probe.quantity == "max" ? worst : (count ? sum / count : 0.0));
      break;
    }
    case ProbeType::temperature:
    case ProbeType::liquid_fraction: {
      // The mass-weighted mean temperature or liquid fraction, or the extreme temperature.
      Real weighted = 0, mass = 0, lowest = std::numeric_limits<Real>::infinity(), highest = -lowest;
      for_each_fluid_particle(model, state, probe.object, [&](Index i) {
        const FluidPhase& phase = model.fluid.phases[state.fluid.phase[i]];
        const Real H = state.fluid.enthalpy[i], m = state.fluid.mass[i];
        const Real value = probe.type == ProbeType::temperature ? fluid_temperature(phase, H) : fluid_liquid_fraction(phase, H);
        weighted += m * value;
        mass += m;
        lowest = std::min(lowest, value);
        highest = std::max(highest, value);
      });
      if (mass == 0) values.push_back(0);
      else values.push_back(probe.quantity == "min" ? lowest : probe.quantity == "max" ? highest : weighted / mass);
      break;
    }
    case ProbeType::particle_count:
    case ProbeType::escaped: {
      Index count = 0;
      for_each_position(model, state, probe.object, [&](const Vec3& x) {
        const bool inside = (x.array() >= probe.box_min.array()).all() && (x.array() <= probe.box_max.array()).all();
        if (probe.type == ProbeType::particle_count || !inside) ++count;
      });
      values.push_back(count);
      break;
    }
    case ProbeType::asleep: {
      Index count = 0;
      for_each_live_particle(model, state, probe.object, [&](Index p) { count += state.sleep.asleep(p); });  // only grains sleep
      values.push_back(count);
      break;
    }
    case ProbeType::momentum:
      push3(probe.quantity == "linear" ? linear_momentum(model, state, probe.object)
                                       : angular_momentum(model, state, probe.object, probe.about));
      break;
    case ProbeType::constraint_error:
      values.push_back(max_constraint_error(model, state, probe.object, probe.family));
      break;
    case ProbeType::body_position: {
      // The origin of the shape's own frame (the scene's "position"), not the centre of mass.
      const Index b = model.objects[probe.object].body;
      const Quat shape_frame = state.rigid.orientation[b] * model.rigid.body_frame_in_shape[b].conjugate();
      push3(state.rigid.position[b] - shape_frame * model.rigid.body_center_in_shape[b]);
      break;
    }
    case ProbeType::body_orientation: {
      const Index b = model.objects[probe.object].body;
      const Quat q = (state.rigid.orientation[b] * model.rigid.body_frame_in_shape[b].conjugate()).normalized();
      values.insert(values.end(), {q.w(), q.x(), q.y(), q.z()});
      break;
    }
    case ProbeType::body_velocity: push3(state.rigid.velocity[model.objects[probe.object].body]); break;
    case ProbeType::body_angular_velocity: push3(state.rigid.angular_velocity[model.objects[probe.object].body]); break;
    case ProbeType::joint_error: {
      JointError worst;
      for (Index j = 0; j < static_cast<Index>(model.joints.size()); ++j) {
        if (probe.joint >= 0 && j != probe.joint) continue;
        // A rod's junctions bend and stretch by design: "*" is the scene's joints.
        if (probe.joint < 0 && model.joints[j].type == JointType::rod) continue;
        const JointError e = joint_error(model.joints[j], state);
        worst.position = std::max(worst.position, e.position);
        worst.angle = std::max(worst.angle, e.angle);
      }
      values.insert(values.end(), {worst.position, worst.angle});
      break;
    }
    case ProbeType::contact_count: {
      values.push_back(touching_contact_count(model, state, probe.object) +
                       touching_particle_body_count(model, state, probe.object));
      break;
    }
    case ProbeType::penetration:
      values.push_back(deepest_penetration(model, state, probe.object));
      break;
    case ProbeType::suction: {
      const SuctionCupState& s = state.suction[probe.cup];
      values.insert(values.end(), {s.sealed ? 1.0 : 0.0, s.pressure_difference, s.volume, s.area});
      break;
    }
    case ProbeType::max_displacement: {
      Real worst = 0;
      for_each_dynamic_body(model, probe.object, [&](Index b) {
        worst = std::max(worst, (state.rigid.position[b] - model.rigid.initial_position[b]).norm());
      });
      for_each_live_particle(model, state, probe.object, [&](Index p) {
        worst = std::max(worst, (state.position[p] - model.particle_rest_position[p]).norm());
      });
      values.push_back(worst);
      break;
    }
  }
}

}  // namespace moreau
