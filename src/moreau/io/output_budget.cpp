#include "moreau/io/output_budget.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <chrono>
#include <filesystem>

#include "moreau/errors.hpp"

namespace moreau {

namespace fs = std::filesystem;

namespace {

const char* const kRunFiles[] = {"probes.csv", "rigid_poses.csv"};

bool written_since(const fs::path& file, fs::file_time_type started) {
  std::error_code ec;
  // File times come from the kernel's coarse clock, which may lag the precise one by a tick.
  return fs::is_regular_file(file, ec) && fs::last_write_time(file, ec) >= started - std::chrono::milliseconds(50);
}

double bytes_written(const fs::path& dir, fs::file_time_type started) {
  std::error_code ec;
  double total = 0;
  if (fs::is_directory(dir / "frames", ec))
    for (const auto& entry : fs::recursive_directory_iterator(dir / "frames", ec))
      if (entry.is_regular_file(ec)) total += static_cast<double>(entry.file_size(ec));
  for (const char* name : kRunFiles)
    if (written_since(dir / name, started)) total += static_cast<double>(fs::file_size(dir / name, ec));
  return total;
}

// Removes what the run wrote; the directory too if nothing else is left in it.
void remove_run_files(const fs::path& dir, fs::file_time_type started) {
  std::error_code ec;
  fs::remove_all(dir / "frames", ec);  // the run cleared it when it began
  for (const char* name : kRunFiles)
    if (written_since(dir / name, started)) fs::remove(dir / name, ec);
  for (const auto& entry : fs::directory_iterator(dir, ec))
    if (entry.path().extension() == ".pvd") fs::remove(entry.path(), ec);
  if (fs::is_empty(dir, ec)) fs::remove(dir, ec);
}

std::string human_bytes(double b) {
  const char* units[] = {"B", "kB", "MB", "GB", "TB", "PB", "EB"};
  int u = 0;
  while (b >= 1000 && u < 6) b /= 1000, ++u;
  return fmt::format("{:.3g} {}", b, units[u]);
}

}  // namespace

long run_step_count(double duration, double dt) {
  const double steps = duration / dt;
  if (!(steps <= 1e15))
    throw InputError(fmt::format("a duration of {:.6g} s in steps of {:.6g} s is {:.3g} steps, more than any run can take "
                                 "(at most 1e15); shorten settings.duration or --duration",
                                 duration, dt, steps));
  return std::max<long>(1, std::lround(steps));
}

void check_output_budget(const std::string& out_dir, long steps, int every, fs::file_time_type started) {
  const fs::path dir(out_dir);
  const double first = bytes_written(dir, started);
  const double samples = 1 + static_cast<double>(steps / every) + (steps % every != 0);
  const double projected = first * samples;
  std::error_code ec;
  const fs::space_info space = fs::space(dir, ec);
  const double available = ec ? 1e300 : static_cast<double>(space.available) + first;
  if (projected > available) {
    remove_run_files(dir, started);
    throw InputError(fmt::format(
        "the run would write {} ({:.3g} steps, {:.3g} outputs of {} each) to '{}', whose file system has {} free; "
        "shorten the run (settings.duration or --duration), write less often (settings.output.every) or write no "
        "frames (settings.output.formats = [])",
        human_bytes(projected), double(steps), samples, human_bytes(first), out_dir, human_bytes(available)));
  }
  if (projected > 1e9)
    fmt::print(stderr, "moreau: warning: this run takes {:.3g} steps and writes about {} to '{}'\n", double(steps),
               human_bytes(projected), out_dir);
}

}  // namespace moreau
