#pragma once
// Writes each object's frame file(s) per output step into DIR/frames/<object>_<NNNNNN>.<ext>, in
// the formats of settings.output.formats (frame_formats.hpp), and with VTK keeps DIR/<scene>.pvd,
// the ParaView collection that ties them together, up to date after every frame (so a run that
// stops early still opens).
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "moreau/io/frame_formats.hpp"
#include "moreau/io/pvd_collection.hpp"
#include "moreau/io/vtk_writer.hpp"
#include "moreau/model/state.hpp"

namespace moreau {

class FrameWriter {
 public:
  /// Starts a series in out_dir, or continues `resume` (a restarted run).
  FrameWriter(const Model& model, std::string out_dir, std::string scene_name, FrameFormats formats,
              FrameSeries resume = {});
  void write(const State& state);
  FrameSeries series() const { return {frames_, pvd_ ? pvd_->bytes() : 0}; }

 private:
  /// Appends every rigid body's pose (shape frame), velocity and angular velocity to
  /// DIR/rigid_poses.csv: one row per body and output step.
  void write_rigid_poses(const State& state);

  const Model& model_;
  std::string out_dir_, scene_name_;
  FrameFormats formats_;
  Real plane_half_size_ = 1;
  int frames_ = 0;
  std::optional<PvdCollection> pvd_;  // with VTK frames only
};

/// Creates the output directory and clears the frames, .pvd files and checkpoint of an earlier run.
void prepare_output_directory(const std::string& dir);

/// Cuts a run's output directory back to a checkpoint: the files it appends rows to to their
/// sizes then, and frames/ to the first `frames.frames` frames (later ones and partial files
/// removed); the engine's frame writer cuts the .pvd back when it continues the series.
void resume_output_directory(const std::string& dir, const FrameSeries& frames,
                             const std::vector<std::pair<std::string, std::uint64_t>>& appended_files);

/// Creates `dir` if missing; an InputError (naming --out) when it cannot be made or written.
void writable_directory(const std::string& dir);

/// `requested`, or out/<scene name> when it is empty.
std::string output_directory_path(const std::string& requested, const std::string& scene_name);

/// A run's output directory, `requested` or out/<scene name>, prepared for the run.
std::string run_output_directory(const std::string& requested, const std::string& scene_name);

}  // namespace moreau
