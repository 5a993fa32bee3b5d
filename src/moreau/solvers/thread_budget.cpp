#include "moreau/solvers/thread_budget.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

namespace moreau {

namespace {

constexpr double kFirstInterval_s = 0.05, kInterval_s = 0.2;  // 5 and 20 clock ticks per core

// Busy and total clock ticks of all cores together, from the first line of /proc/stat:
//   cpu user nice system idle iowait irq softirq steal ...
bool read_system_ticks(std::uint64_t& busy, std::uint64_t& total) {
  std::ifstream in("/proc/stat");
  std::string label;
  if (!(in >> label) || label != "cpu") return false;
  std::uint64_t value = 0, idle = 0;
  busy = total = 0;
  for (int field = 0; field < 8 && in >> value; ++field) {
    total += value;
    if (field == 3 || field == 4) idle += value;  // idle, iowait
  }
  busy = total - idle;
  return total > 0;
}

// This process's user and system ticks: fields 14 and 15 of /proc/self/stat (after the command
// name, which is in parentheses and may hold spaces).
bool read_own_ticks(std::uint64_t& ticks) {
  std::ifstream in("/proc/self/stat");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto close = text.rfind(')');
  if (close == std::string::npos) return false;
  std::istringstream rest(text.substr(close + 2));
  std::string field;
  std::uint64_t utime = 0, stime = 0;
  for (int i = 3; i <= 15 && rest >> field; ++i) {
    if (i == 14) utime = std::stoull(field);
    if (i == 15) stime = std::stoull(field);
  }
  ticks = utime + stime;
  return true;
}

}  // namespace

ThreadBudget::ThreadBudget(int requested) {
  cores_ = std::max(1, omp_get_num_procs());
  requested_ = requested > 0 ? requested : std::max(1, omp_get_max_threads());
  current_ = requested_;
  last_ = std::chrono::steady_clock::now();
  measure();
}

void ThreadBudget::measure() {
  std::uint64_t busy = 0, total = 0, self = 0;
  if (!read_system_ticks(busy, total) || !read_own_ticks(self)) return;
  if (have_sample_ && total > last_total_) {
    // Cores kept busy by other processes = (all busy ticks - ours) / ticks per core.
    const double per_core = double(total - last_total_) / cores_;
    const double others = std::max(0.0, double(busy - last_busy_) - double(self - last_self_)) / per_core;
    const int free_cores = std::max(1, cores_ - static_cast<int>(std::lround(others)));
    current_ = std::clamp(free_cores, 1, requested_);
  }
  last_busy_ = busy;
  last_total_ = total;
  last_self_ = self;
  have_sample_ = true;
  ++measurements_;
}

int ThreadBudget::next_step_threads() {
  const auto now = std::chrono::steady_clock::now();
  const double interval = measurements_ < 2 ? kFirstInterval_s : kInterval_s;
  if (requested_ > 1 && std::chrono::duration<double>(now - last_).count() >= interval) {
    last_ = now;
    measure();
  }
  return current_;
}

}  // namespace moreau
