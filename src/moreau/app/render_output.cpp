#include "moreau/app/render_output.hpp"

#include <fmt/format.h>
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <stdlib.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <condition_variable>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "moreau/app/output_server.hpp"
#include "moreau/errors.hpp"
#include "moreau/io/atomic_file.hpp"

extern char** environ;

namespace moreau {
namespace fs = std::filesystem;

namespace {

// The first of `names` found on PATH, or nothing.
std::optional<std::string> find_program(std::initializer_list<const char*> names) {
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path ? path : "/usr/bin:/bin");
  std::vector<std::string> entries;
  for (std::string dir; std::getline(dirs, dir, ':');) entries.push_back(dir.empty() ? "." : dir);
  for (const char* name : names)
    for (const std::string& dir : entries) {
      const fs::path candidate = fs::path(dir) / name;
      if (access(candidate.c_str(), X_OK) == 0) return candidate.string();
    }
  return std::nullopt;
}

std::string chromium_program() {
  if (const char* chosen = std::getenv("MOREAU_CHROMIUM")) return chosen;
  if (auto found = find_program({"chromium", "chromium-browser", "google-chrome"})) return *found;
  throw std::runtime_error("moreau render draws with Chromium, which is not on PATH: install Debian's chromium "
                           "package (scripts/install-deps.sh does) or set MOREAU_CHROMIUM to a Chrome or Chromium");
}

// Runs `argv` with its output in `log`; returns its process id.
pid_t spawn(const std::vector<std::string>& argv, const std::string& log) {
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  posix_spawn_file_actions_t files;
  posix_spawn_file_actions_init(&files);
  posix_spawn_file_actions_addopen(&files, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&files, STDOUT_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&files, STDOUT_FILENO, STDERR_FILENO);
  pid_t pid = 0;
  const int error = posix_spawn(&pid, argv[0].c_str(), &files, nullptr, args.data(), environ);
  posix_spawn_file_actions_destroy(&files);
  if (error != 0) throw std::runtime_error(fmt::format("cannot start {}: {}", argv[0], std::strerror(error)));
  return pid;
}

// The last lines of a log, to show when a helper program failed.
std::string tail_of(const std::string& log, std::size_t lines = 8) {
  std::ifstream in(log);
  std::vector<std::string> all;
  for (std::string line; std::getline(in, line);) all.push_back(line);
  std::string out;
  for (std::size_t i = all.size() > lines ? all.size() - lines : 0; i < all.size(); ++i) out += "\n  " + all[i];
  return out;
}

// What the page has posted back.
struct PageReport {
  std::mutex mutex;
  std::condition_variable changed;
  std::vector<std::string> pictures;  // files written, in order
  bool done = false;
  std::string bad_input, error;
};

// A private temporary directory (Chromium's profile and log).
struct TemporaryDirectory {
  fs::path path;
  TemporaryDirectory() {
    std::string pattern = (fs::temp_directory_path() / "moreau-render-XXXXXX").string();
    if (!mkdtemp(pattern.data())) throw std::runtime_error("cannot create a temporary directory");
    path = pattern;
  }
  ~TemporaryDirectory() {
    std::error_code ignored;
    fs::remove_all(path, ignored);
  }
};

}  // namespace

std::string render_output(const RenderOptions& options) {
  check_output_directory(options.output_dir);
  if (options.width < 16 || options.height < 16 || options.width > 8192 || options.height > 8192)
    throw InputError(fmt::format("--size {}x{}: each side must be 16 to 8192 pixels", options.width, options.height));
  const bool video = !options.video.empty();
  std::string ffmpeg;
  if (video) {
    const auto found = find_program({"ffmpeg"});
    if (!found) throw std::runtime_error("--video needs ffmpeg, which is not on PATH (Debian's ffmpeg package)");
    ffmpeg = *found;
  }
  const std::string chromium = chromium_program();
  const fs::path dir = options.output_dir;
  const std::string name = output_scene_name(options.output_dir);
  const fs::path pictures_dir = dir / "render";

  if (options.all_frames || video) {
    // A video is every picture named <scene>_NNNNNN.png from 0 on: remove an earlier render's.
    std::error_code ignored;
    if (fs::is_directory(pictures_dir, ignored))
      for (const auto& entry : fs::directory_iterator(pictures_dir))
        if (entry.path().extension() == ".png" && entry.path().stem().string().rfind(name + "_", 0) == 0)
          fs::remove(entry.path(), ignored);
  }

  PageReport report;
  OutputServer server(options.output_dir, viewer_page_directory());
  server.on_post([&](const std::string& what, const std::string& body) {
    std::lock_guard lock(report.mutex);
    if (what.rfind("frame_", 0) == 0) {
      const bool one = !options.all_frames && !video && !options.out.empty();
      const fs::path file = one ? fs::path(options.out) : pictures_dir / fmt::format("{}_{}.png", name, what.substr(6));
      if (file.has_parent_path()) fs::create_directories(file.parent_path());
      write_file_atomically(file.string(), body);
      report.pictures.push_back(file.string());
    } else if (what == "done") {
      report.done = true;
    } else if (what == "bad_input") {
      report.bad_input = body;
    } else {
      report.error = body.empty() ? what : body;
    }
    report.changed.notify_all();
  });
  const std::string frames = options.all_frames || video ? "all" : options.frame < 0 ? "last" : std::to_string(options.frame);
  std::string url = server.start(0) + fmt::format("?render={}&width={}&height={}", frames, options.width, options.height);
  if (!options.colour_by.empty()) url += "&colour=" + options.colour_by;

  TemporaryDirectory temporary;
  const std::string log = (temporary.path / "chromium.log").string();
  std::vector<std::string> argv = {chromium, "--headless=new", "--use-angle=swiftshader", "--enable-unsafe-swiftshader",
                                   "--hide-scrollbars", "--mute-audio", "--no-first-run",
                                   "--user-data-dir=" + (temporary.path / "profile").string(),
                                   // The page draws W x H whatever the window; a larger window holds it whole.
                                   fmt::format("--window-size={},{}", options.width + 64, options.height + 256)};
  if (geteuid() == 0) argv.push_back("--no-sandbox");  // Chromium refuses to run as root with its sandbox
  argv.push_back(url);
  const pid_t browser = spawn(argv, log);

  // Wait for the page's posts; give up when Chromium dies or nothing arrives for too long.
  std::string failure;
  {
    std::unique_lock lock(report.mutex);
    auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(options.timeout_s);
    std::size_t seen = 0;
    while (!report.done && report.bad_input.empty() && report.error.empty()) {
      report.changed.wait_for(lock, std::chrono::milliseconds(200));
      if (report.pictures.size() > seen) {
        seen = report.pictures.size();
        deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10) +
                   std::chrono::duration<double>(options.timeout_s / 4);
      }
      int status = 0;
      if (waitpid(browser, &status, WNOHANG) == browser) {
        failure = "Chromium stopped before the page finished" + tail_of(log);
        break;
      }
      if (std::chrono::steady_clock::now() > deadline) {
        failure = fmt::format("the page drew nothing for {:.0f} s (Chromium's last words:{})", options.timeout_s, tail_of(log));
        break;
      }
    }
  }
  kill(browser, SIGTERM);
  waitpid(browser, nullptr, 0);
  server.stop();
  if (!report.bad_input.empty()) throw InputError(fmt::format("{}: {}", options.output_dir, report.bad_input));
  if (!report.error.empty()) throw std::runtime_error("the viewer page failed: " + report.error);
  if (!failure.empty()) throw std::runtime_error(failure);

  if (!video) return report.pictures.size() == 1 ? report.pictures[0] : pictures_dir.string();
  // H.264 wants even sides; the pad adds a pixel where one is odd.
  const std::string encode_log = (temporary.path / "ffmpeg.log").string();
  const pid_t encoder = spawn({ffmpeg, "-y", "-loglevel", "error", "-framerate", "30", "-i",
                               (pictures_dir / (name + "_%06d.png")).string(), "-vf",
                               "pad=ceil(iw/2)*2:ceil(ih/2)*2", "-c:v", "libx264", "-pix_fmt", "yuv420p", options.video},
                              encode_log);
  int status = 0;
  waitpid(encoder, &status, 0);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw std::runtime_error(fmt::format("ffmpeg could not encode {}:{}", options.video, tail_of(encode_log)));
  return options.video;
}

}  // namespace moreau
