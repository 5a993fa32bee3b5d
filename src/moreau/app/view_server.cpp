#include "moreau/app/view_server.hpp"

#include <fmt/format.h>
#include <httplib.h>
#include <signal.h>
#include <spawn.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <thread>
#include <vector>

#include "moreau/errors.hpp"

extern char** environ;

namespace moreau {
namespace fs = std::filesystem;

namespace {

bool has_page(const fs::path& dir) { return fs::is_regular_file(dir / "index.html"); }

// What the page needs to know about the directory: its .pvd collections (the frames), whether it
// has probes, and the scene's name (the first collection's stem).
nlohmann::json manifest(const fs::path& dir) {
  std::vector<std::string> collections;
  for (const auto& entry : fs::directory_iterator(dir))
    if (entry.is_regular_file() && entry.path().extension() == ".pvd") collections.push_back(entry.path().filename());
  std::sort(collections.begin(), collections.end());
  nlohmann::json m;
  m["directory"] = fs::absolute(dir).lexically_normal().string();
  m["scene"] = collections.empty() ? dir.filename().string() : fs::path(collections[0]).stem().string();
  m["collections"] = collections;
  m["probes"] = fs::is_regular_file(dir / "probes.csv") ? nlohmann::json("probes.csv") : nlohmann::json(nullptr);
  m["run"] = fs::is_regular_file(dir / "run.json") ? nlohmann::json("run.json") : nlohmann::json(nullptr);
  return m;
}

// A run's output directory the viewer can play: a directory with at least one .pvd.
void check_output_directory(const fs::path& dir) {
  std::error_code error;
  if (!fs::exists(dir, error))
    throw InputError(fmt::format("{}: no such directory; give the output directory of a run (moreau run writes "
                                 "out/<scene name> unless --out says otherwise)",
                                 dir.string()));
  if (!fs::is_directory(dir, error))
    throw InputError(fmt::format("{}: not a directory; give a run's output directory, e.g. out/showcase", dir.string()));
  if (manifest(dir)["collections"].empty())
    throw InputError(fmt::format(
        "{}: no .pvd file, so there are no VTK frames to play; run a scene whose settings.output.formats includes "
        "\"vtk\" (the default) into this directory",
        dir.string()));
}

// Opens `url` in the desktop's browser when there is a display; the page's address is printed
// either way.
void open_in_browser(const std::string& url) {
  if (!std::getenv("DISPLAY") && !std::getenv("WAYLAND_DISPLAY")) return;
  pid_t pid = 0;
  const char* argv[] = {"xdg-open", url.c_str(), nullptr};
  if (posix_spawnp(&pid, "xdg-open", nullptr, nullptr, const_cast<char**>(argv), environ) != 0)
    fmt::print(stderr, "moreau: could not start xdg-open; open the address above in a browser\n");
}

}  // namespace

std::string viewer_page_directory() {
  std::vector<fs::path> candidates;
  if (const char* dir = std::getenv("MOREAU_VIEWER_DIR")) candidates.emplace_back(dir);
  std::error_code error;
  const fs::path program = fs::read_symlink("/proc/self/exe", error);
  if (!error) {
    candidates.push_back(program.parent_path() / "viewer");
    candidates.push_back(program.parent_path().parent_path() / "share" / "moreau" / "viewer");
  }
  std::string looked;
  for (const fs::path& dir : candidates) {
    if (has_page(dir)) return dir.string();
    looked += (looked.empty() ? "" : ", ") + dir.string();
  }
  throw std::runtime_error(fmt::format("the viewer's page (index.html) is not in {}; `make build` builds it into "
                                       "build/viewer (it needs npm), or set MOREAU_VIEWER_DIR",
                                       looked.empty() ? "any known place" : looked));
}

void serve_output(const ViewOptions& options) {
  const fs::path dir = options.output_dir;
  check_output_directory(dir);
  const std::string page = options.viewer_dir.empty() ? viewer_page_directory() : options.viewer_dir;
  if (!has_page(page)) throw std::runtime_error(fmt::format("{}: no viewer page (index.html) there", page));

  httplib::Server server;
  for (const char* ext : {"vtu", "vtp", "pvd", "bin"}) server.set_file_extension_and_mimetype_mapping(ext, "application/octet-stream");
  server.set_file_extension_and_mimetype_mapping("csv", "text/csv");
  // A run may write into the directory while the page is open: never let the browser cache a frame.
  server.set_post_routing_handler([](const httplib::Request&, httplib::Response& res) {
    res.set_header("Cache-Control", "no-store");
  });
  server.Get("/manifest.json", [dir](const httplib::Request&, httplib::Response& res) {
    res.set_content(manifest(dir).dump(), "application/json");
  });
  // The output directory under /data/ (httplib refuses paths that leave it), the page at /.
  if (!server.set_mount_point("/data", dir.string()) || !server.set_mount_point("/", page))
    throw std::runtime_error("could not serve " + dir.string());

  const std::string host = "127.0.0.1";
  const int port = options.port == 0 ? server.bind_to_any_port(host) : (server.bind_to_port(host, options.port) ? options.port : -1);
  if (port < 0) throw std::runtime_error(fmt::format("cannot listen on {}:{} (is the port in use?)", host, options.port));

  // SIGINT and SIGTERM are waited for here, on the main thread; the server's threads inherit the
  // blocked mask, so the signal reaches sigwait and the server is stopped from outside its loop.
  sigset_t stop_signals;
  sigemptyset(&stop_signals);
  sigaddset(&stop_signals, SIGINT);
  sigaddset(&stop_signals, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &stop_signals, nullptr);
  std::thread listener([&server] { server.listen_after_bind(); });

  const std::string url = fmt::format("http://{}:{}/", host, port);
  fmt::print("moreau: serving {} at {} (Ctrl-C to stop)\n", dir.string(), url);
  std::fflush(stdout);
  if (options.open_browser) open_in_browser(url);

  int received = 0;
  sigwait(&stop_signals, &received);
  server.stop();
  listener.join();
  pthread_sigmask(SIG_UNBLOCK, &stop_signals, nullptr);
}

}  // namespace moreau
