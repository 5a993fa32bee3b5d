#pragma once
// Output files that are whole or absent: written to "<path>.part" and renamed over <path> when
// complete (rename is atomic within a directory on POSIX), so a run that is killed, crashes or
// runs out of disk mid-write never leaves a truncated frame, .pvd, run.json or checkpoint behind.
#include <fstream>
#include <string>

namespace moreau {

class AtomicFile {
 public:
  /// Opens "<path>.part" for writing (binary); std::runtime_error if it cannot be created.
  explicit AtomicFile(std::string path);
  /// Removes the partial file if commit() was not reached.
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  std::ofstream& stream() { return out_; }
  /// Closes the file and renames it into place; std::runtime_error naming the file if a write failed.
  void commit();

 private:
  std::string path_, part_;
  std::ofstream out_;
  bool committed_ = false;
};

/// Writes `bytes` to `path` through an AtomicFile.
void write_file_atomically(const std::string& path, const std::string& bytes);

}  // namespace moreau
