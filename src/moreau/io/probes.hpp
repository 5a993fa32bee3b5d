#pragma once
// Probes: named measurements written to probes.csv, one row per output step. Scalars give one
// column `<name>`, vectors three columns `<name>.x, <name>.y, <name>.z`.
#include <optional>
#include <string>
#include <vector>

#include "moreau/model/diagnostics.hpp"

namespace moreau {

enum class ProbeType {
  point, energy, center_of_mass, extent, momentum, constraint_error,
  fluid_height, density_error, particle_count, escaped,
  body_position, body_orientation, body_velocity, body_angular_velocity,  // one rigid body
  joint_error, contact_count, max_displacement, penetration,
  suction,  // one suction cup: sealed (0/1), pressure difference (Pa), volume (m^3), sealed area (m^2)
  rod_point, rod_twist,  // a rod's centreline point ("point" on a rod); its twist (rad)
  angle_of_repose, mass_flow,  // a pile's surface slope (degrees); the mass through a plane (kg/s or kg)
  asleep,  // sleeping grains (settings.sleep)
  runout,  // how far a pile reaches from its axis (m)
  temperature, liquid_fraction  // thermal fluids (fluid_heat.hpp): K; the mass-weighted share that is liquid
};

struct Probe {
  std::string name;
  ProbeType type = ProbeType::point;
  Index object = -1;                 // -1: every object ("*")
  std::string quantity;              // point: position|displacement|velocity; energy: kinetic|potential|elastic|total;
                                     // extent: min|max; momentum: linear|angular; density_error: mean|max;
                                     // temperature: mean|min|max
  Index particle = -1;               // point probes: global particle index
  int axis = 1;                      // extent
  Vec3 about = Vec3::Zero();         // angular momentum reference point, m
  std::string family = "all";        // constraint_error: a family's kErrorName, or "all"
  Vec3 at = Vec3::Zero();            // fluid_height: a point on the vertical line measured, m
  Vec3 box_min = Vec3::Zero(), box_max = Vec3::Zero();  // escaped: particles outside this box are counted
  Index joint = -1;                  // joint_error: one joint, or -1 for every joint
  Index cup = -1;                    // suction: index into Model::suction_cups
  Index rod = -1, rod_point = -1;    // rod_point, rod_twist: index into Model::rods; its centreline point
  std::optional<Vec3> pile_axis;     // angle_of_repose: a point on the pile's axis (default: its centre of mass), m
  Real ring_width = 0;               // angle_of_repose: the rings' width, m
  std::optional<std::pair<Vec3, Vec3>> pile_region;  // angle_of_repose: only particles in this box (min, max), m
  Real resting_speed = 0;            // angle_of_repose: only particles slower than this (m/s; 0: all)
  std::optional<Vec3> runout_direction;  // runout: a horizontal unit vector to measure along (else radially)
  Real runout_fraction = 0.99;       // runout: the share of the particles within the runout
  Vec3 plane_point = Vec3::Zero(), plane_normal = Vec3::UnitY();  // mass_flow; quantity rate|beyond

  bool is_vector() const;
  /// Number of columns the probe writes.
  int width() const;
};

/// Column headers of one probe.
std::vector<std::string> probe_columns(const Probe& probe);

/// Appends the probe's current value(s) to `values`.
void evaluate_probe(const Probe& probe, const Model& model, const State& state, std::vector<Real>& values);

}  // namespace moreau
