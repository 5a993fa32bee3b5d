#pragma once
// Wall-clock time per named stage of a step, accumulated over a run (reported as stage_time_s).
#include <array>
#include <chrono>
#include <string_view>

namespace moreau {

enum class Stage : int {
  detect_contacts,
  predict,
  distance,
  bending,
  triangle_strain,
  neo_hookean,
  tet_volume,
  attachments,
  collider_contacts,
  particle_contacts,
  joints,
  rigid_contacts,
  fluid_neighbors,
  fluid_density,
  update_velocity,
  velocity_pass,
  fluid_velocity,
  check_state,
  count
};

inline constexpr std::array<std::string_view, static_cast<int>(Stage::count)> kStageNames{
    "detect_contacts", "predict",           "distance",          "bending",         "triangle_strain",
    "neo_hookean",     "tet_volume",        "attachments",       "collider_contacts", "particle_contacts", "joints", "rigid_contacts",
    "fluid_neighbors", "fluid_density",     "update_velocity",   "velocity_pass",     "fluid_velocity",
    "check_state"};

class StageTimer {
 public:
  using Clock = std::chrono::steady_clock;
  void start() { last_ = Clock::now(); }
  /// Charges the time since the previous lap (or start) to `stage`.
  void lap(Stage stage) {
    const auto now = Clock::now();
    seconds_[static_cast<int>(stage)] += std::chrono::duration<double>(now - last_).count();
    last_ = now;
  }
  double seconds(Stage stage) const { return seconds_[static_cast<int>(stage)]; }

 private:
  Clock::time_point last_{};
  std::array<double, static_cast<int>(Stage::count)> seconds_{};
};

}  // namespace moreau
