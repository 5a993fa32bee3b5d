#pragma once
// Serves a run's output directory and the viewer page (viewer/, bundled at build time) over HTTP on
// the loopback interface: `moreau view` for a browser, `moreau render` for a headless one. The page
// reads the directory's .pvd collections, VTK frames and probes.csv under /data/ as they are on
// disk; /manifest.json tells it which of them there are.
#include <functional>
#include <memory>
#include <string>

namespace moreau {

/// The directory holding the built viewer page (index.html, viewer.js): $MOREAU_VIEWER_DIR, else
/// `viewer/` beside the program, else `../share/moreau/viewer` from it. Throws std::runtime_error
/// naming where it looked when none has index.html.
std::string viewer_page_directory();

/// Throws InputError unless `dir` is a run's output directory with VTK frames (a .pvd).
void check_output_directory(const std::string& dir);

/// The scene's name in a run's output directory: its first .pvd's stem (by name), or the
/// directory's own name when it has none.
std::string output_scene_name(const std::string& dir);

class OutputServer {
 public:
  /// Serves `output_dir` under /data/ and the page in `page_dir` at /.
  OutputServer(const std::string& output_dir, const std::string& page_dir);
  ~OutputServer();
  OutputServer(const OutputServer&) = delete;
  OutputServer& operator=(const OutputServer&) = delete;

  /// Accepts POST /render/<name> requests (a rendered image, or "done" and "error" messages):
  /// `handler(name, body)`. Set before start().
  void on_post(std::function<void(const std::string& name, const std::string& body)> handler);
  /// Listens on 127.0.0.1:`port` (0: any free port) on a thread of its own; returns the page's
  /// address. Throws std::runtime_error when the port cannot be bound.
  std::string start(int port);
  void stop();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// `moreau view`: serves until SIGINT or SIGTERM, printing the page's address first and, when
/// `open_browser` and there is a display, opening it with xdg-open.
void view_output(const std::string& output_dir, int port, bool open_browser);

}  // namespace moreau
