#pragma once
// Writes one .vtu per object and output step into DIR/frames/ and keeps DIR/<scene>.pvd, the
// ParaView collection that ties them together, up to date after every frame (so a run that stops
// early still opens).
#include <string>
#include <vector>

#include "moreau/io/vtk_writer.hpp"
#include "moreau/model/state.hpp"

namespace moreau {

class FrameWriter {
 public:
  FrameWriter(const Model& model, std::string out_dir, std::string scene_name);
  void write(const State& state);
  int frames_written() const { return frame_; }

 private:
  /// Appends every rigid body's pose (shape frame), velocity and angular velocity to
  /// DIR/rigid_poses.csv: one row per body and output step.
  void write_rigid_poses(const State& state);

  const Model& model_;
  std::string out_dir_, scene_name_;
  Real plane_half_size_ = 1;
  int frame_ = 0;
  std::vector<PvdEntry> entries_;
};

/// File-system-safe version of a scene or object name.
std::string safe_file_name(const std::string& name);

/// Creates the output directory and clears the frames and .pvd files of an earlier run.
void prepare_output_directory(const std::string& dir);

/// Creates `dir` if missing; an InputError (naming --out) when it cannot be made or written.
void writable_directory(const std::string& dir);

/// A run's output directory, `requested` or out/<scene name>, prepared for the run.
std::string run_output_directory(const std::string& requested, const std::string& scene_name);

}  // namespace moreau
