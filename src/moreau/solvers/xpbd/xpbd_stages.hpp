#pragma once
// The stages of an XPBD step, in the order they run (xpbd_step.cpp). The particle constraint
// families each have their own stage, numbered after the fixed ones in family-list order.
#include <string>
#include <vector>

#include "moreau/constraints/particle_families.hpp"

namespace moreau {

enum class XpbdStage : int {
  detect_contacts,
  predict,
  fluid_neighbors,
  fluid_density,
  particle_contacts,
  collider_contacts,
  joints,
  rigid_contacts,
  update_velocity,
  velocity_pass,
  fluid_velocity,
  fluid_heat,
  check_state,
  shape_matching,
  sleep,
  count
};

/// The stage of family `family` (its index in ParticleFamilies).
constexpr int xpbd_family_stage(int family) { return static_cast<int>(XpbdStage::count) + family; }

/// Every stage's name, indexed by stage number.
inline std::vector<std::string> xpbd_stage_names() {
  std::vector<std::string> names{"detect_contacts",   "predict",        "fluid_neighbors", "fluid_density",
                                 "particle_contacts", "collider_contacts", "joints",       "rigid_contacts",
                                 "update_velocity",   "velocity_pass",  "fluid_velocity",  "fluid_heat",
                                 "check_state",       "shape_matching", "sleep"};
  for (std::string_view family : particle_family_names()) names.emplace_back(family);
  return names;
}

}  // namespace moreau
