#pragma once
// A ParaView collection (.pvd) grown one frame at a time. Each frame's entries are written over
// the closing tags, followed by new closing tags, in one write: the file is a valid collection
// after every frame, and memory and the bytes written per frame stay constant. (Rewriting the
// whole file per frame wrote O(frames^2) bytes — 7 GB over 2,400 frames of 18 bodies — and kept
// every entry in memory.)
#include <cstdint>
#include <string>
#include <vector>

#include "moreau/math/types.hpp"

namespace moreau {

/// One file of a frame: its time, the object's place in the scene (`part`) and its path relative
/// to the .pvd.
struct PvdEntry {
  Real time;
  int part;
  std::string file;
};

/// The frames a run has written: how many, and where the .pvd's entries end (its size without the
/// closing tags). A checkpoint records it; a run restarted in the same output directory cuts the
/// .pvd back to it and continues the series.
struct FrameSeries {
  int frames = 0;
  std::uint64_t pvd_bytes = 0;
};

class PvdCollection {
 public:
  /// Starts an empty collection at `path`, or (resume.frames > 0) continues the one there from
  /// the end of resume's entries.
  PvdCollection(std::string path, const FrameSeries& resume);
  /// Appends one frame's entries.
  void add_frame(const std::vector<PvdEntry>& entries);
  /// Where the entries end (the size of the file without its closing tags).
  std::uint64_t bytes() const { return end_; }

 private:
  std::string path_;
  std::uint64_t end_ = 0;
};

}  // namespace moreau
