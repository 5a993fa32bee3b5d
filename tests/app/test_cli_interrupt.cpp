// A run stopped by SIGINT or SIGTERM stops after its current step with exit 128 + the signal,
// writes a checkpoint and a run.json marked "interrupted", and leaves every frame whole and the
// .pvd valid (every file it lists exists, no partial files); `--restart` then finishes the run in
// the same output directory, whose probes.csv, rigid_poses.csv, .pvd and frames are then those
// of a run that was never interrupted. A checkpoint of another scene is refused with exit 2.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <regex>

#include "scene_test_helpers.hpp"
#include "test_helpers.hpp"

namespace moreau {
namespace {

namespace fs = std::filesystem;

const std::string kScene = std::string(MOREAU_SOURCE_DIR) + "/scenes/tablecloth.json";

std::string file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Starts a run in the background (its output to `log`), waits until probes.csv has `rows` lines,
// sends `signal`, and returns the run's exit code.
int run_and_signal(const std::string& out, const std::string& log, const char* signal, int rows) {
  const std::string script = fmt::format(
      "{} run {} --out {} --quiet --set settings.duration=2 > {} 2>&1 & pid=$!; "
      "for i in $(seq 1 6000); do "
      "  if [ -f {}/probes.csv ] && [ $(wc -l < {}/probes.csv) -ge {} ]; then break; fi; sleep 0.01; "
      "done; kill -{} $pid; wait $pid; exit $?",
      MOREAU_BINARY, kScene, out, log, out, out, rows, signal);
  const int status = std::system(("sh -c '" + script + "'").c_str());
  return WEXITSTATUS(status);
}

// Every file the .pvd lists exists and is a whole VTK file; no partial file is left.
void expect_whole_output(const std::string& out) {
  const std::string pvd = file_bytes(out + "/tablecloth.pvd");
  ASSERT_NE(pvd.find("</VTKFile>"), std::string::npos);
  const std::regex entry("file=\"([^\"]+)\"");
  int listed = 0;
  for (auto it = std::sregex_iterator(pvd.begin(), pvd.end(), entry); it != std::sregex_iterator(); ++it, ++listed) {
    const std::string frame = file_bytes(out + "/" + (*it)[1].str());
    EXPECT_NE(frame.rfind("</VTKFile>"), std::string::npos) << (*it)[1].str() << " is not whole";
  }
  EXPECT_GT(listed, 0);
  for (const auto& f : fs::recursive_directory_iterator(out))
    EXPECT_NE(f.path().extension(), ".part") << f.path() << " was left behind";
}

TEST(CliInterrupt, SignalStopsAfterTheStepAndRestartFinishesTheSameRun) {
  const std::string dir = test::temp_dir("cli-interrupt");
  const auto reference = test::run_moreau(fmt::format("run {} --out {}/reference --quiet --set settings.duration=2", kScene, dir));
  ASSERT_EQ(reference.exit_code, 0) << reference.output;

  for (const auto& [signal, code] : {std::pair<const char*, int>{"INT", 130}, {"TERM", 143}}) {
    const std::string out = dir + "/" + signal;
    EXPECT_EQ(run_and_signal(out, dir + "/log.txt", signal, 30), code) << file_bytes(dir + "/log.txt");
    const nlohmann::json run = nlohmann::json::parse(file_bytes(out + "/run.json"));
    EXPECT_EQ(run["status"], "interrupted");
    EXPECT_LT(run["steps"].get<long>(), 120) << "the run finished before the signal: the test did not interrupt it";
    EXPECT_EQ(run["checkpoint"], "checkpoint.bin");
    EXPECT_NE(file_bytes(dir + "/log.txt").find("resume with:"), std::string::npos);
    expect_whole_output(out);

    // With --out, or without it: a restart continues the directory of its checkpoint.
    const std::string where = std::string(signal) == "INT" ? " --out " + out : std::string();
    const auto resumed = test::run_moreau(
        fmt::format("run {}{} --quiet --set settings.duration=2 --restart {}/checkpoint.bin", kScene, where, out));
    ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
    EXPECT_EQ(nlohmann::json::parse(file_bytes(out + "/run.json"))["status"], "completed");
    for (const char* file : {"probes.csv", "rigid_poses.csv", "tablecloth.pvd"})
      EXPECT_EQ(file_bytes(out + "/" + file), file_bytes(dir + "/reference/" + file)) << signal << ": " << file;
    std::vector<std::string> frames, reference_frames;
    for (const auto& f : fs::directory_iterator(out + "/frames")) frames.push_back(f.path().filename().string());
    for (const auto& f : fs::directory_iterator(dir + "/reference/frames")) reference_frames.push_back(f.path().filename().string());
    std::sort(frames.begin(), frames.end());
    std::sort(reference_frames.begin(), reference_frames.end());
    EXPECT_EQ(frames, reference_frames) << signal;
    ASSERT_FALSE(frames.empty());
    EXPECT_EQ(file_bytes(out + "/frames/" + frames.back()), file_bytes(dir + "/reference/frames/" + frames.back()));
  }

  // A checkpoint restores only into its own scene: exit 2 naming the file, nothing written.
  const std::string other = std::string(MOREAU_SOURCE_DIR) + "/scenes/stack_knockdown.json";
  const auto refused = test::run_moreau(fmt::format("run {} --out {}/other --quiet --restart {}/INT/checkpoint.bin", other, dir, dir));
  EXPECT_EQ(refused.exit_code, 2) << refused.output;
  EXPECT_NE(refused.output.find("written for scene 'tablecloth'"), std::string::npos) << refused.output;
  EXPECT_FALSE(fs::exists(dir + "/other"));
}

}  // namespace
}  // namespace moreau
