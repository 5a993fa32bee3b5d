#pragma once
// The stages of an NMD step, in the order they run (nmd_step.cpp).
#include <string>
#include <vector>

namespace moreau {

enum class NmdStage : int { detect_contacts, fluid_neighbors, assemble, solve, integrate, fluid_velocity, check_state, sleep, count };

inline std::vector<std::string> nmd_stage_names() {
  return {"detect_contacts", "fluid_neighbors", "assemble", "solve", "integrate", "fluid_velocity", "check_state", "sleep"};
}

}  // namespace moreau
