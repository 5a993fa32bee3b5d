#pragma once
// Wall-clock time per stage of a step, accumulated over a run (reported as stage_time_s). A
// solver numbers its stages and names them (e.g. xpbd_stage_names()); the timer only adds time.
#include <chrono>
#include <type_traits>
#include <vector>

namespace moreau {

class StageTimer {
 public:
  using Clock = std::chrono::steady_clock;
  void start() { last_ = Clock::now(); }
  /// Charges the time since the previous lap (or start) to stage `stage`.
  void lap(int stage) {
    const auto now = Clock::now();
    if (stage >= static_cast<int>(seconds_.size())) seconds_.resize(stage + 1, 0.0);
    seconds_[stage] += std::chrono::duration<double>(now - last_).count();
    last_ = now;
  }
  template <class Stage>
    requires std::is_enum_v<Stage>
  void lap(Stage stage) { lap(static_cast<int>(stage)); }
  double seconds(int stage) const { return stage < static_cast<int>(seconds_.size()) ? seconds_[stage] : 0.0; }

 private:
  Clock::time_point last_{};
  std::vector<double> seconds_;
};

}  // namespace moreau
