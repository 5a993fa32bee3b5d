#pragma once
// Readers that take a path get the fuzzer's bytes through a file of their own (one per process,
// rewritten for every input).
#include <unistd.h>

#include <cstdint>
#include <fstream>
#include <string>

namespace moreau::fuzz {

/// Writes `size` bytes to <tmp>/moreau-fuzz-<pid>-<tag><suffix> and returns its path.
inline std::string input_file(const uint8_t* data, size_t size, const std::string& tag, const std::string& suffix) {
  const char* tmp = std::getenv("TMPDIR");
  const std::string path = std::string(tmp ? tmp : "/tmp") + "/moreau-fuzz-" + std::to_string(getpid()) + "-" + tag + suffix;
  std::ofstream(path, std::ios::binary | std::ios::trunc).write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  return path;
}

}  // namespace moreau::fuzz
