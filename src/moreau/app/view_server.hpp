#pragma once
// `moreau view DIR`: serves a run's output directory and the viewer page (viewer/, bundled at build
// time) on the loopback interface, so a browser plays the run back without ParaView and without a
// network. The page reads the directory's .pvd collections, VTK frames and probes.csv as they are
// on disk; /manifest.json tells it which of them there are.
#include <string>

namespace moreau {

struct ViewOptions {
  std::string output_dir;     // a run's output directory (has a .pvd)
  int port = 0;               // 0: any free port
  bool open_browser = true;   // with a display, open the page in the desktop's browser (xdg-open)
  std::string viewer_dir;     // the built page; empty: found next to the program (viewer_page_directory)
};

/// The directory holding the built viewer page (index.html, viewer.js): $MOREAU_VIEWER_DIR, else
/// `viewer/` beside the program, else `../share/moreau/viewer` from it. Throws std::runtime_error
/// naming where it looked when none has index.html.
std::string viewer_page_directory();

/// Serves until SIGINT or SIGTERM, printing the page's address first. Throws InputError when
/// `output_dir` is not a run's output directory with VTK frames, std::runtime_error when the port
/// cannot be bound.
void serve_output(const ViewOptions& options);

}  // namespace moreau
