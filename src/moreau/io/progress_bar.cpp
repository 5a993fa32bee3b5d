#include "moreau/io/progress_bar.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstdio>

namespace moreau {

void ProgressBar::update(double time, long steps, double wall_time_s) {
  if (!enabled_) return;
  const auto now = std::chrono::steady_clock::now();
  if (drawn_ && now - last_draw_ < std::chrono::milliseconds(100) && time < duration_) return;
  last_draw_ = now;
  drawn_ = true;
  const double fraction = std::clamp(time / duration_, 0.0, 1.0);
  constexpr int kWidth = 30;
  const int filled = static_cast<int>(fraction * kWidth);
  const double rate = wall_time_s > 0 ? steps / wall_time_s : 0;
  const double eta = fraction > 0 ? wall_time_s * (1 - fraction) / fraction : 0;
  fmt::print(stderr, "\r[{}{}] t = {:.3f} / {:.3f} s  {:.0f} steps/s  ETA {:.0f} s   ", std::string(filled, '#'),
             std::string(kWidth - filled, ' '), time, duration_, rate, eta);
  std::fflush(stderr);
}

void ProgressBar::finish() {
  if (enabled_ && drawn_) fmt::print(stderr, "\n");
}

}  // namespace moreau
