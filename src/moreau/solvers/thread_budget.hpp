#pragma once
// How many threads a step may use. moreau's steps run many short parallel loops separated by
// barriers; when another process keeps a core busy, a thread on that core is descheduled for whole
// time slices and every barrier waits for it (two threads then took 3 to 40 times as long as
// one). The budget is the requested count less the cores that other processes kept busy over the
// last measurement interval, re-measured after 0.05 s and then every 0.2 s of wall time from /proc/stat (all
// cores) and /proc/self/stat (this process). Results do not depend on the thread count, so the
// count may change between steps without changing the answer.
#include <chrono>
#include <cstdint>

namespace moreau {

class ThreadBudget {
 public:
  /// `requested`: the most threads to use (0 = all cores).
  explicit ThreadBudget(int requested);
  /// The thread count for the next step.
  int next_step_threads();

 private:
  void measure();
  int requested_ = 1, cores_ = 1, current_ = 1;
  std::chrono::steady_clock::time_point last_;
  std::uint64_t last_busy_ = 0, last_total_ = 0, last_self_ = 0;
  bool have_sample_ = false;
  int measurements_ = 0;
};

}  // namespace moreau
