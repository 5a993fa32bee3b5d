#pragma once
// probes.csv: the time series of a run's probes, one row per sample (every engine writes it).
#include <fstream>
#include <string>
#include <vector>

#include "moreau/math/types.hpp"

namespace moreau {

/// Every probe's column names in order, columns_of(probe) giving one probe's.
template <class Item, class ColumnsOf>
std::vector<std::string> probe_table_columns(const std::vector<Item>& probes, ColumnsOf columns_of) {
  std::vector<std::string> columns;
  for (const Item& p : probes)
    for (std::string& c : columns_of(p)) columns.push_back(std::move(c));
  return columns;
}

class ProbeCsv {
 public:
  /// Creates dir/probes.csv with the header "time,<columns>", or appends to it (a restarted run
  /// continuing its output directory).
  ProbeCsv(const std::string& dir, const std::vector<std::string>& columns, bool append = false);
  /// One row: the time (9 significant digits) and the values (17, round-trip exact).
  void write_row(double time, const std::vector<Real>& values);
  /// Writes what is buffered (for measuring the file's size).
  void flush() { out_.flush(); }

 private:
  std::ofstream out_;
};

}  // namespace moreau
