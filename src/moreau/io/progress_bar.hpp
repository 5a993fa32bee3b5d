#pragma once
// A one-line progress bar on stderr: simulated time, steps per second and the estimated time left.
// Redrawn at most ten times a second; silent when disabled (not a terminal, or --quiet).
#include <chrono>

namespace moreau {

class ProgressBar {
 public:
  ProgressBar(bool enabled, double duration) : enabled_(enabled), duration_(duration) {}
  void update(double time, long steps, double wall_time_s);
  void finish();

 private:
  bool enabled_;
  double duration_;
  bool drawn_ = false;
  std::chrono::steady_clock::time_point last_draw_{};
};

}  // namespace moreau
