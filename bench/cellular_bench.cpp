// The cellular model at scale: a 1000 x 1000 wrapped grid diffusing through `rate`
// (classic RK4, one step per world step), in cell updates per second (cells x steps),
// against the same computation written directly in C++, so the ratio says how close
// the engine is to the hand-written limit. Both run on one thread and on all cores.

#include <benchmark/benchmark.h>
#include <sys/resource.h>

#include <algorithm>
#include <cmath>
#include <thread>
#include <vector>

#include "bench/bench_support.h"
#include "core/world.h"

namespace ontogen::bench {
namespace {

constexpr int kSide = 1000;
constexpr double kD = 0.2;
constexpr double kStep = 0.5;
constexpr int kSteps = 4;

const char* kDiffusion = R"(
#define D 0.2
cell U(u = 0) { rules { rate(u) = D * (sum(u) - count() * u); } }
system plate { pool grid(1000, 1000) wrap vonneumann; fill U(sin(me.x * 0.01) + cos(me.y * 0.02)); }
)";

double totalOf(std::span<const double> values) {
  double total = 0;
  for (double v : values) total += v;
  return total;
}

void BM_GridDiffusionThroughRate(benchmark::State& state) {
  static const Compiled compiled = compileText("diffusion.cell", kDiffusion);
  if (!compiled.program) {
    state.SkipWithError(compiled.error.c_str());
    return;
  }
  WorldDef def = kBenchWorld;
  def.threads = static_cast<unsigned>(state.range(0));
  FirstAndWarm firstAndWarm;
  for (auto _ : state) {
    state.PauseTiming();
    World world(compiled.program, def);
    const double before = totalOf(world.rootPool().stateArena());
    state.ResumeTiming();
    const double start = processSeconds();
    world.advanceTo(kSteps * kStep, kStep);
    const double seconds = processSeconds() - start;
    state.PauseTiming();
    firstAndWarm.add(seconds);
    // Diffusion on a torus conserves the total: a wrong engine would not.
    if (std::abs(totalOf(world.rootPool().stateArena()) - before) > 1e-6 * kSide * kSide) {
      state.SkipWithError("the total changed: diffusion is wrong");
      return;
    }
    state.ResumeTiming();
  }
  state.counters["updates/s"] =
      benchmark::Counter(static_cast<double>(kSide) * kSide * kSteps, benchmark::Counter::kIsIterationInvariantRate);
  firstAndWarm.report(state);
}
BENCHMARK(BM_GridDiffusionThroughRate)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond)->Iterations(3)->UseRealTime();

// The same: RK4 over a 5-point Laplacian on a torus, with flat arrays.
void derivative(const std::vector<double>& u, std::vector<double>& du) {
  for (int y = 0; y < kSide; ++y) {
    const int up = (y + kSide - 1) % kSide * kSide, down = (y + 1) % kSide * kSide, row = y * kSide;
    for (int x = 0; x < kSide; ++x) {
      const int left = (x + kSide - 1) % kSide, right = (x + 1) % kSide;
      du[row + x] = kD * (u[up + x] + u[row + left] + u[row + right] + u[down + x] - 4 * u[row + x]);
    }
  }
}

void BM_GridDiffusionHandWritten(benchmark::State& state) {
  const size_t n = static_cast<size_t>(kSide) * kSide;
  std::vector<double> u(n), k1(n), k2(n), k3(n), k4(n), tmp(n);
  for (auto _ : state) {
    for (int y = 0; y < kSide; ++y)
      for (int x = 0; x < kSide; ++x) u[y * kSide + x] = std::sin(x * 0.01) + std::cos(y * 0.02);
    for (int step = 0; step < kSteps; ++step) {
      derivative(u, k1);
      for (size_t i = 0; i < n; ++i) tmp[i] = u[i] + 0.5 * kStep * k1[i];
      derivative(tmp, k2);
      for (size_t i = 0; i < n; ++i) tmp[i] = u[i] + 0.5 * kStep * k2[i];
      derivative(tmp, k3);
      for (size_t i = 0; i < n; ++i) tmp[i] = u[i] + kStep * k3[i];
      derivative(tmp, k4);
      for (size_t i = 0; i < n; ++i) u[i] += kStep / 6 * (k1[i] + 2 * k2[i] + 2 * k3[i] + k4[i]);
    }
    benchmark::DoNotOptimize(u.data());
  }
  state.counters["updates/s"] =
      benchmark::Counter(static_cast<double>(n) * kSteps, benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_GridDiffusionHandWritten)->Unit(benchmark::kMillisecond)->Iterations(3)->UseRealTime();

}  // namespace
}  // namespace ontogen::bench
