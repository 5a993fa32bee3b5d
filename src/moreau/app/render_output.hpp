#pragma once
// `moreau render DIR`: pictures of a run without a display. The viewer page draws the frames in
// headless Chromium (software WebGL) and posts each picture back to the program, which writes it
// as PNG; with ffmpeg, every frame becomes an MP4.
#include <string>

namespace moreau {

struct RenderOptions {
  std::string output_dir;     // a run's output directory (has a .pvd)
  int frame = -1;             // the frame to draw, 0 the first; -1 the last
  bool all_frames = false;    // every frame, DIR/render/<scene>_NNNNNN.png
  std::string video;          // with all frames: encode them into this MP4 (ffmpeg)
  std::string out;            // the PNG of one frame (default DIR/render/<scene>_NNNNNN.png)
  std::string colour_by;      // a point array to colour by; empty: each object in its colour
  int width = 1280, height = 720;
  double timeout_s = 120;     // for the page to load; each frame adds 10 s
};

/// Renders and returns the files written (the PNG, or the MP4). Throws InputError for a bad
/// directory or frame number, std::runtime_error when Chromium or ffmpeg is missing or fails.
std::string render_output(const RenderOptions& options);

}  // namespace moreau
