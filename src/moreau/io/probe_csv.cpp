#include "moreau/io/probe_csv.hpp"

#include <fmt/format.h>

namespace moreau {

ProbeCsv::ProbeCsv(const std::string& dir, const std::vector<std::string>& columns, bool append)
    : out_(dir + "/probes.csv", append ? std::ios::app : std::ios::trunc) {
  if (append) return;
  out_ << "time";
  for (const std::string& c : columns) out_ << ',' << c;
  out_ << '\n';
}

void ProbeCsv::write_row(double time, const std::vector<Real>& values) {
  out_ << fmt::format("{:.9g}", time);
  for (Real v : values) out_ << fmt::format(",{:.17g}", v);
  out_ << '\n';
}

}  // namespace moreau
