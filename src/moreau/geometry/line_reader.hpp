#pragma once
// Reading text mesh files line by line with errors that name the file and the line.
#include <fmt/format.h>

#include <fstream>
#include <sstream>
#include <string>

#include "moreau/errors.hpp"

namespace moreau {

inline std::ifstream open_or_throw(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(fmt::format("{}: cannot open mesh file (does it exist and is it readable?)", path));
  return in;
}

/// A line reader that skips blank lines and '#' comments and knows its line number.
struct LineReader {
  std::ifstream in;
  std::string path;
  int line_number = 0;

  bool next(std::istringstream& line) {
    std::string text;
    while (std::getline(in, text)) {
      ++line_number;
      const auto hash = text.find('#');
      if (hash != std::string::npos) text.resize(hash);
      if (text.find_first_not_of(" \t\r") == std::string::npos) continue;
      line.clear();
      line.str(text);
      return true;
    }
    return false;
  }
  [[noreturn]] void fail(const std::string& what) const {
    throw InputError(fmt::format("{}:{}: {}", path, line_number, what));
  }
};

}  // namespace moreau
