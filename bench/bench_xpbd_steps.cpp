// Step-time benchmarks for the XPBD solver on the two reference scenes of issue 2:
//   cloth_50x50     a 50 x 50 particle cloth, 10 m x 10 m, two corners pinned, unit masses,
//                   stretch + dihedral bending, dt 0.005 s, 5 substeps x 1 iteration
//                   (and the same with isometric bending);
//   fem_bar_30x5x5  a 30 x 5 x 5 node Neo-Hookean bar (2,320 tetrahedra), one end clamped,
//                   same dt and substeps.
// Each benchmark loads its scene from bench/scenes/, runs 10 warm-up steps, then times every
// step of a fixed-length run. Besides Google Benchmark's mean time it reports the median and the
// slowest step (ms), the 99th percentile over the median, and the share of each solver stage, so
// fork/join stalls show up as max_over_median. The argument is the OpenMP thread count.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <string>
#include <vector>

#include "moreau/moreau.hpp"
#include "moreau/scene/scene.hpp"
#include "moreau/solvers/xpbd/xpbd_step.hpp"

namespace {

using moreau::Real;

constexpr int kWarmupSteps = 10;

std::string bench_scene(const std::string& name) { return std::string(MOREAU_SOURCE_DIR) + "/bench/scenes/" + name; }

// The reference library gives every cloth particle a mass of 1 kg (pinned ones: infinite).
void set_unit_masses(moreau::Model& model) {
  for (moreau::Index p = 0; p < model.particle_count(); ++p) {
    model.particle_mass[p] = 1.0;
    if (model.particle_inv_mass[p] > 0) model.particle_inv_mass[p] = 1.0;
  }
}

void run_steps(benchmark::State& bench, const std::string& scene_file, bool unit_masses,
               const std::vector<std::string>& overrides = {}) {
  auto sim = moreau::Simulation::load(bench_scene(scene_file), overrides);
  moreau::Scene& scene = sim.internals();
  scene.model.settings.threads = static_cast<int>(bench.range(0));
  if (unit_masses) set_unit_masses(scene.model);

  moreau::StageTimer warmup_timer, timer;
  for (int s = 0; s < kWarmupSteps; ++s) moreau::xpbd_step(scene.model, scene.state, warmup_timer);

  std::vector<double> step_ms;
  step_ms.reserve(static_cast<size_t>(bench.max_iterations));
  for (auto _ : bench) {
    const auto start = std::chrono::steady_clock::now();
    moreau::xpbd_step(scene.model, scene.state, timer);
    step_ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
  }

  std::vector<double> sorted = step_ms;
  std::sort(sorted.begin(), sorted.end());
  const double median = sorted[sorted.size() / 2], slowest = sorted.back();
  bench.counters["median_ms"] = median;
  bench.counters["max_ms"] = slowest;
  bench.counters["max_over_median"] = slowest / median;
  bench.counters["p99_over_median"] = sorted[sorted.size() * 99 / 100] / median;
  double total = 0;
  for (int s = 0; s < static_cast<int>(moreau::Stage::count); ++s) total += timer.seconds(static_cast<moreau::Stage>(s));
  for (int s = 0; s < static_cast<int>(moreau::Stage::count); ++s) {
    const double share = timer.seconds(static_cast<moreau::Stage>(s)) / total;
    if (share >= 0.01) bench.counters[std::string(moreau::kStageNames[s]) + "_%"] = 100 * share;
  }
}

void BM_Cloth50x50(benchmark::State& bench) { run_steps(bench, "cloth_50x50.json", true); }
void BM_Cloth50x50Isometric(benchmark::State& bench) {
  run_steps(bench, "cloth_50x50.json", true, {"objects.cloth.material.bending_model=\"isometric\""});
}
void BM_FemBar30x5x5(benchmark::State& bench) { run_steps(bench, "fem_bar_30x5x5.json", false); }

// 2,000 steps = 10 s of simulated time: the cloth falls, swings and settles; the bar sags and rings.
BENCHMARK(BM_Cloth50x50)->Arg(1)->Arg(2)->Iterations(2000)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Cloth50x50Isometric)->Arg(1)->Arg(2)->Iterations(2000)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_FemBar30x5x5)->Arg(1)->Arg(2)->Iterations(2000)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
