#include "moreau/app/output_server.hpp"

#include <fmt/format.h>
#include <httplib.h>
#include <signal.h>
#include <spawn.h>

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

std::vector<std::string> collections_in(const fs::path& dir) {
  std::vector<std::string> collections;
  for (const auto& entry : fs::directory_iterator(dir))
    if (entry.is_regular_file() && entry.path().extension() == ".pvd") collections.push_back(entry.path().filename());
  std::sort(collections.begin(), collections.end());
  return collections;
}

// What the page needs to know about the directory: its .pvd collections (the frames), whether it
// has probes, and the scene's name (the first collection's stem).
nlohmann::json manifest(const fs::path& dir) {
  const std::vector<std::string> collections = collections_in(dir);
  nlohmann::json m;
  m["directory"] = fs::absolute(dir).lexically_normal().string();
  m["scene"] = output_scene_name(dir);
  m["collections"] = collections;
  m["probes"] = fs::is_regular_file(dir / "probes.csv") ? nlohmann::json("probes.csv") : nlohmann::json(nullptr);
  return m;
}

// Opens `url` in the desktop's browser when there is a display.
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

std::string output_scene_name(const std::string& path) {
  const fs::path dir = path;
  const std::vector<std::string> collections = collections_in(dir);
  return collections.empty() ? dir.filename().string() : fs::path(collections[0]).stem().string();
}

void check_output_directory(const std::string& path) {
  const fs::path dir = path;
  std::error_code error;
  if (!fs::exists(dir, error))
    throw InputError(fmt::format("{}: no such directory; give the output directory of a run (moreau run writes "
                                 "out/<scene name> unless --out says otherwise)",
                                 path));
  if (!fs::is_directory(dir, error))
    throw InputError(fmt::format("{}: not a directory; give a run's output directory, e.g. out/showcase", path));
  if (collections_in(dir).empty())
    throw InputError(fmt::format(
        "{}: no .pvd file, so there are no VTK frames to show; run a scene whose settings.output.formats includes "
        "\"vtk\" (the default) into this directory",
        path));
}

struct OutputServer::Impl {
  httplib::Server server;
  std::thread listener;
};

OutputServer::OutputServer(const std::string& output_dir, const std::string& page_dir) : impl_(std::make_unique<Impl>()) {
  httplib::Server& server = impl_->server;
  for (const char* ext : {"vtu", "vtp", "pvd", "bin"}) server.set_file_extension_and_mimetype_mapping(ext, "application/octet-stream");
  server.set_file_extension_and_mimetype_mapping("csv", "text/csv");
  // A run may write into the directory while the page is open: never let the browser cache a frame.
  server.set_post_routing_handler([](const httplib::Request&, httplib::Response& res) {
    res.set_header("Cache-Control", "no-store");
  });
  const fs::path dir = output_dir;
  server.Get("/manifest.json", [dir](const httplib::Request&, httplib::Response& res) {
    res.set_content(manifest(dir).dump(), "application/json");
  });
  // The output directory under /data/ (httplib refuses paths that leave it), the page at /.
  if (!server.set_mount_point("/data", output_dir) || !server.set_mount_point("/", page_dir))
    throw std::runtime_error(fmt::format("cannot serve {} and {}", output_dir, page_dir));
}

OutputServer::~OutputServer() { stop(); }

void OutputServer::on_post(std::function<void(const std::string&, const std::string&)> handler) {
  impl_->server.Post(R"(/render/([A-Za-z0-9_]+))", [handler](const httplib::Request& req, httplib::Response& res) {
    handler(req.matches[1], req.body);
    res.set_content("ok", "text/plain");
  });
}

std::string OutputServer::start(int port) {
  const std::string host = "127.0.0.1";
  httplib::Server& server = impl_->server;
  const int bound = port == 0 ? server.bind_to_any_port(host) : (server.bind_to_port(host, port) ? port : -1);
  if (bound < 0) throw std::runtime_error(fmt::format("cannot listen on {}:{} (is the port in use?)", host, port));
  impl_->listener = std::thread([&server] { server.listen_after_bind(); });
  return fmt::format("http://{}:{}/", host, bound);
}

void OutputServer::stop() {
  if (!impl_->listener.joinable()) return;
  impl_->server.stop();
  impl_->listener.join();
}

void view_output(const std::string& output_dir, int port, bool open_browser) {
  check_output_directory(output_dir);
  // SIGINT and SIGTERM are waited for here, on the main thread; the server's threads, started
  // after, inherit the blocked mask, so the signal reaches sigwait and the server stops cleanly.
  sigset_t stop_signals;
  sigemptyset(&stop_signals);
  sigaddset(&stop_signals, SIGINT);
  sigaddset(&stop_signals, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &stop_signals, nullptr);
  OutputServer server(output_dir, viewer_page_directory());
  const std::string url = server.start(port);
  fmt::print("moreau: serving {} at {} (Ctrl-C to stop)\n", output_dir, url);
  std::fflush(stdout);
  if (open_browser) open_in_browser(url);
  int received = 0;
  sigwait(&stop_signals, &received);
  server.stop();
  pthread_sigmask(SIG_UNBLOCK, &stop_signals, nullptr);
}

}  // namespace moreau
