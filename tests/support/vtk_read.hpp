#pragma once
// Reads the arrays moreau's VTK XML writers put in the raw appended section back into numbers,
// for tests that check written files value for value.
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <regex>
#include <string>
#include <vector>

namespace moreau::test {

/// The appended Float64 array `name` of a .vtu or .vtp file (empty if there is none).
inline std::vector<double> read_appended_float64(const std::string& path, const std::string& name) {
  std::ifstream in(path, std::ios::binary);
  const std::string file((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::smatch m;
  const std::regex array("Name=\"" + name + "\"[^>]*offset=\"([0-9]+)\"");
  if (!std::regex_search(file, m, array)) return {};
  const size_t data_start = file.find("<AppendedData encoding=\"raw\">\n_") + std::strlen("<AppendedData encoding=\"raw\">\n_");
  const size_t at = data_start + std::stoull(m[1]);
  std::uint64_t bytes = 0;
  std::memcpy(&bytes, file.data() + at, sizeof(bytes));
  std::vector<double> values(bytes / sizeof(double));
  std::memcpy(values.data(), file.data() + at + sizeof(bytes), bytes);
  return values;
}

}  // namespace moreau::test
