// The spatial pool's neighbour index at growing sizes and constant density: rebuilding
// the bucket grid and answering every cell's neighbour query. If the index stays fast at
// a million cells, the time per cell is about the same at 10^4, 10^5 and 10^6.

#include <benchmark/benchmark.h>

#include <cmath>
#include <random>
#include <vector>

#include "pools/spatial_pool.h"

namespace ontogen::bench {
namespace {

// n cells uniformly in a square whose area grows with n: about 3 neighbours within the
// radius of 1 for every cell, as in a packed colony.
SpatialPool makePool(size_t n) {
  SpatialPool pool(1.0, {{0, 1, -1}});
  const double side = std::sqrt(static_cast<double>(n) * 3.14159 / 3.0);
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> coordinate(0, side);
  for (size_t i = 0; i < n; ++i) {
    const double p[2] = {coordinate(random), coordinate(random)};
    pool.append({.master = 0, .birth = 0, .id = i}, p, 2);
  }
  return pool;
}

void BM_SpatialIndexAndQueries(benchmark::State& state) {
  const size_t n = static_cast<size_t>(state.range(0));
  SpatialPool pool = makePool(n);
  std::vector<uint32_t> found;
  size_t neighbours = 0;
  for (auto _ : state) {
    pool.index();
    neighbours = 0;
    for (size_t i = 0; i < n; ++i) {
      pool.neighbours(i, found);
      neighbours += found.size();
    }
    benchmark::DoNotOptimize(neighbours);
  }
  const double mean = static_cast<double>(neighbours) / static_cast<double>(n);
  if (mean < 2 || mean > 4) state.SkipWithError("the density is not the intended one");
  state.counters["neighbours/cell"] = mean;
  state.counters["cells/s"] = benchmark::Counter(static_cast<double>(n), benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_SpatialIndexAndQueries)->Arg(10'000)->Arg(100'000)->Arg(1'000'000)->Unit(benchmark::kMillisecond);

// The same queries as the engine asks them for a step's rules or rates: every cell's
// neighbours at once, in bucket order (SpatialPool::neighbourTable).
void BM_SpatialNeighbourTable(benchmark::State& state) {
  const size_t n = static_cast<size_t>(state.range(0));
  SpatialPool pool = makePool(n);
  LargeVector<uint32_t> offsets, cells;
  for (auto _ : state) {
    pool.index();
    pool.neighbourTable(offsets, cells);
    benchmark::DoNotOptimize(cells.data());
  }
  const double mean = static_cast<double>(cells.size()) / static_cast<double>(n);
  if (mean < 2 || mean > 4) state.SkipWithError("the density is not the intended one");
  state.counters["neighbours/cell"] = mean;
  state.counters["cells/s"] = benchmark::Counter(static_cast<double>(n), benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_SpatialNeighbourTable)->Arg(10'000)->Arg(100'000)->Arg(1'000'000)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace ontogen::bench
