// Neighbour search on the issue-3 dam-break block: a 1 m cube of particles on a lattice of
// spacing 2r (r = 0.015625 m: 31^3 = 29,791 particles; r = 0.01 m: 49^3 = 117,649), search
// radius h = 4r (the kernel support used by the fluid solver). Argument: thread count.
#include <benchmark/benchmark.h>

#include "moreau/geometry/neighbor_search.hpp"

namespace {

std::vector<moreau::Vec3> lattice_cube(moreau::Real r) {
  const int n = static_cast<int>(1.0 / (2 * r) + 0.5) - 1;  // as the reference scene counts them
  std::vector<moreau::Vec3> x;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k) x.emplace_back(2 * r * i, 2 * r * j, 2 * r * k);
  return x;
}

void run(benchmark::State& bench, moreau::Real r) {
  const auto x = lattice_cube(r);
  moreau::NeighborSearch search;
  search.build(x, 4 * r, static_cast<int>(bench.range(0)));  // warm the buffers
  for (auto _ : bench) search.build(x, 4 * r, static_cast<int>(bench.range(0)));
  bench.counters["particles"] = static_cast<double>(x.size());
  bench.counters["neighbors_per_particle"] = static_cast<double>(search.total()) / x.size();
}

void BM_NeighborSearch30k(benchmark::State& bench) { run(bench, 0.015625); }
void BM_NeighborSearch118k(benchmark::State& bench) { run(bench, 0.01); }

BENCHMARK(BM_NeighborSearch30k)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_NeighborSearch118k)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
