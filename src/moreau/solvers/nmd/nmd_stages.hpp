#pragma once
// The stages of an NMD step, in the order they run (nmd_step.cpp).
#include <string>
#include <vector>

namespace moreau {

enum class NmdStage : int { detect_contacts, assemble, solve, integrate, check_state, count };

inline std::vector<std::string> nmd_stage_names() {
  return {"detect_contacts", "assemble", "solve", "integrate", "check_state"};
}

}  // namespace moreau
