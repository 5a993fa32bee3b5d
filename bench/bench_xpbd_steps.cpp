// Step-time benchmarks for the XPBD solver on the reference scenes of issues 2 and 3:
//   cloth_50x50     a 50 x 50 particle cloth, 10 m x 10 m, two corners pinned, unit masses,
//                   stretch + dihedral bending, dt 0.005 s, 5 substeps x 1 iteration
//                   (and the same with isometric bending);
//   fem_bar_30x5x5  a 30 x 5 x 5 node Neo-Hookean bar (2,320 tetrahedra), one end clamped,
//                   same dt and substeps;
//   dam_break_30k / dam_break_120k  SPlisHSPlasH's stock dam break (1 m water cube in a
//                   4 x 3 x 1.5 m tank), 29,791 / 117,649 particles, dt 1 ms, 1 substep x 3
//                   Jacobi iterations (issue 3's targets; also reports ms per density iteration);
//   pyramid_210 / boxes_1000 / chain_100_released  issue 4's rigid-body scenes (60 Hz; 8, 8 and
//                   20 substeps; bench/scenes/generate_rigid_scenes.py).
// Each benchmark loads its scene from bench/scenes/ into a moreau::World (the public API), runs 10
// warm-up steps, then times every step of a fixed-length run. Besides Google Benchmark's mean time it reports the median and the
// slowest step (ms), the 99th percentile over the median, and the share of each solver stage, so
// fork/join stalls show up as max_over_median. The argument is the OpenMP thread count.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "moreau/moreau.hpp"

namespace {

constexpr int kWarmupSteps = 10;

std::string bench_scene(const std::string& name) { return std::string(MOREAU_SOURCE_DIR) + "/bench/scenes/" + name; }

// Steps a scene through the public World API on bench.range(0) threads: kWarmupSteps untimed,
// then one timed step per benchmark iteration.
void run_steps(benchmark::State& bench, const std::string& scene_file, const std::vector<std::string>& overrides = {}) {
  moreau::World world = moreau::World::load(bench_scene(scene_file), overrides);
  const int threads = static_cast<int>(bench.range(0));
  for (int s = 0; s < kWarmupSteps; ++s) world.step(threads);
  const std::map<std::string, double> warmup = world.stage_times();

  std::vector<double> step_ms;
  step_ms.reserve(static_cast<size_t>(bench.max_iterations));
  for (auto _ : bench) {
    const auto start = std::chrono::steady_clock::now();
    world.step(threads);
    step_ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
  }

  std::vector<double> sorted = step_ms;
  std::sort(sorted.begin(), sorted.end());
  const double median = sorted[sorted.size() / 2], slowest = sorted.back();
  bench.counters["median_ms"] = median;
  bench.counters["max_ms"] = slowest;
  bench.counters["max_over_median"] = slowest / median;
  bench.counters["p99_over_median"] = sorted[sorted.size() * 99 / 100] / median;
  // Stage shares of the timed steps (the warm-up's time taken off).
  std::map<std::string, double> timed = world.stage_times();
  double total = 0;
  for (auto& [stage, seconds] : timed) total += (seconds -= warmup.at(stage));
  for (const auto& [stage, seconds] : timed)
    if (seconds / total >= 0.01) bench.counters[stage + "_%"] = 100 * seconds / total;
  const long fluid_particles = world.array("fluid.position").count;
  if (fluid_particles > 0) {
    // Per Jacobi iteration of the density constraint (lambda pass + correction pass + apply), and
    // throughput in particle-steps per second.
    const nlohmann::json settings = nlohmann::json::parse(std::ifstream(bench_scene(scene_file)))["settings"];
    const double iterations = static_cast<double>(step_ms.size()) * settings["substeps"].get<int>() *
                              settings["iterations"].get<int>();
    bench.counters["ms_per_density_iteration"] = 1e3 * timed.at("fluid_density") / iterations;
    bench.counters["Mparticle_steps_per_s"] = fluid_particles / (median * 1e3);
  }
}

void BM_Cloth50x50(benchmark::State& bench) { run_steps(bench, "cloth_50x50.json"); }
void BM_Cloth50x50Isometric(benchmark::State& bench) {
  run_steps(bench, "cloth_50x50.json", {"objects.cloth.material.bending_model=\"isometric\""});
}
void BM_FemBar30x5x5(benchmark::State& bench) { run_steps(bench, "fem_bar_30x5x5.json"); }
void BM_DamBreak30k(benchmark::State& bench) { run_steps(bench, "dam_break_30k.json"); }
void BM_DamBreak120k(benchmark::State& bench) { run_steps(bench, "dam_break_120k.json"); }
void BM_Pyramid210(benchmark::State& bench) { run_steps(bench, "pyramid_210.json"); }
void BM_Boxes1000(benchmark::State& bench) { run_steps(bench, "boxes_1000.json"); }
void BM_ChainReleased(benchmark::State& bench) { run_steps(bench, "chain_100_released.json"); }

// 2,000 steps = 10 s of simulated time: the cloth falls, swings and settles; the bar sags and rings.
BENCHMARK(BM_Cloth50x50)->Arg(1)->Arg(2)->Iterations(2000)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Cloth50x50Isometric)->Arg(1)->Arg(2)->Iterations(2000)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_FemBar30x5x5)->Arg(1)->Arg(2)->Iterations(2000)->Unit(benchmark::kMillisecond)->UseRealTime();
// Issue 3's dam break (SPlisHSPlasH's stock scene): 490 timed steps after 10 warm-up = 0.5 s.
BENCHMARK(BM_DamBreak30k)->Arg(1)->Arg(2)->Iterations(490)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_DamBreak120k)->Arg(1)->Arg(2)->Iterations(490)->Unit(benchmark::kMillisecond)->UseRealTime();
// Issue 4: the pyramid's 10 s, the boxes' and the chain's first 5 s (600 / 300 steps with warm-up).
BENCHMARK(BM_Pyramid210)->Arg(1)->Arg(2)->Iterations(590)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Boxes1000)->Arg(1)->Arg(2)->Iterations(290)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_ChainReleased)->Arg(1)->Iterations(290)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
