// A long run keeps its memory flat: run for ten times a scene's duration through the run loop
// (frames, probes and all), sampling the process's resident memory every 20 ms from another
// thread. After the warm-up (the first tenth of the run's wall time: buffers, contact sets and neighbour
// lists reach their working size) the resident size may not grow by more than 4 MB: what the
// output bookkeeping legitimately adds (the .pvd's list, ~100 bytes a frame) stays far below it,
// while a leak of even one small allocation per step (2,400 steps or more) would pass it.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <thread>

#include "moreau/moreau.hpp"
#include "test_helpers.hpp"

namespace moreau::test {
namespace {

namespace fs = std::filesystem;

double resident_mb() {
  std::ifstream statm("/proc/self/statm");
  long pages = 0, resident = 0;
  statm >> pages >> resident;
  return resident * static_cast<double>(sysconf(_SC_PAGESIZE)) / 1e6;
}

struct LongRun {
  const char* name;
  const char* scene;
  std::vector<std::string> overrides;
};

class MemoryFlat : public ::testing::TestWithParam<LongRun> {};

TEST_P(MemoryFlat, ResidentMemoryStaysFlatOverTenDurations) {
  const LongRun& c = GetParam();
  const fs::path scene = fs::path(MOREAU_SOURCE_DIR) / "scenes" / c.scene;
  World world = World::load(scene.string(), c.overrides);
  const double duration = nlohmann::json::parse(std::ifstream(scene))["settings"].value("duration", 1.0);
  RunOptions options;
  options.out_dir = temp_dir(std::string("memory-") + c.name);
  options.duration = 10 * duration;

  // (wall seconds since the start, resident MB), sampled while the run steps.
  std::atomic<bool> done{false};
  std::vector<std::pair<double, double>> samples;
  const auto start = std::chrono::steady_clock::now();
  auto seconds = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  std::thread sampler([&] {
    while (!done) {
      samples.emplace_back(seconds(), resident_mb());
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
  });
  world.run(options);
  done = true;
  sampler.join();
  samples.emplace_back(seconds(), resident_mb());

  const double warm_up = 0.1 * samples.back().first;  // the first tenth of the run
  double after_warm_up = -1, peak = 0;
  for (const auto& [t, rss] : samples) {
    if (t < warm_up) continue;
    if (after_warm_up < 0) after_warm_up = rss;
    peak = std::max(peak, rss);
  }
  ASSERT_GE(after_warm_up, 0) << "no sample after the warm-up";
  std::printf("%s: %zu samples over %.3g s simulated in %.1f s; resident %.1f MB after warm-up, %.1f MB at most later\n",
              c.name, samples.size(), world.time(), samples.back().first, after_warm_up, peak);
  EXPECT_LT(peak - after_warm_up, 4.0) << c.name << ": resident memory grew during the run";
}

INSTANTIATE_TEST_SUITE_P(Scenes, MemoryFlat,
                         ::testing::Values(LongRun{"RigidStack", "stack_knockdown.json", {}},
                                           LongRun{"Fluid", "dam_break.json", {"objects.water.particle_radius=0.03"}},
                                           LongRun{"Cloth", "tablecloth.json", {"objects.cloth.mesh.resolution=[12,12]"}}),
                         [](const auto& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace moreau::test
