#include "moreau/scene/memory_estimate.hpp"

#include <fmt/format.h>
#include <unistd.h>

namespace moreau {

namespace {

double physical_memory_bytes() {
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
  return pages > 0 && page > 0 ? double(pages) * double(page) : 0;
}

double& configured_limit() {
  static double limit = 0;  // 0: the default
  return limit;
}

}  // namespace

double memory_limit_bytes() {
  if (configured_limit() > 0) return configured_limit();
  const double physical = physical_memory_bytes();
  return physical > 0 ? 0.8 * physical : 1e300;
}

void set_memory_limit_bytes(double bytes) { configured_limit() = bytes; }

void check_memory(const SpecPlace& at, const std::string& key, double count, double bytes_each, const std::string& items) {
  const double estimate = count * bytes_each, limit = memory_limit_bytes();
  if (estimate <= limit) return;
  const std::string origin = configured_limit() > 0 ? "set by --memory-limit"
                                                    : fmt::format("80 % of this machine's {:.3g} GB", physical_memory_bytes() / 1e9);
  at.fail(key, fmt::format("{:.3g} {} need at least {:.3g} GB ({:.0f} bytes each), more than the memory limit of {:.3g} GB ({}); "
                           "use fewer, or raise the limit with --memory-limit <GB>",
                           count, items, estimate / 1e9, bytes_each, limit / 1e9, origin));
}

}  // namespace moreau
