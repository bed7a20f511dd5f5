// The cellular model at scale: a 1000 x 1000 wrapped grid diffusing through `rate`
// (classic RK4, one step per world step), in cell updates per second (cells x steps),
// against the same computation written directly in C++, so the ratio says how close
// the engine is to the hand-written limit. Both run on one thread and on all cores.
// Gray-Scott on 64 x 64 is the small grid beside it.

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

// Gray-Scott (models/gray_scott.cell) on its 64 x 64 wrapped grid: a small grid, where
// what a step costs besides the arithmetic shows. kGrayScottSteps steps of dt = 1.
constexpr int kGrayScottSteps = 500;

const Compiled& grayScott() {
  static const Compiled compiled = compileModel("gray_scott.cell");
  return compiled;
}

// The model's state after kGrayScottSteps through a World (u, v interleaved, cell by cell).
std::vector<double> grayScottThroughWorld() {
  World world(grayScott().program, kBenchWorld);
  world.advanceTo(kGrayScottSteps, 1.0);
  const auto state = world.rootPool().stateArena();
  return {state.begin(), state.end()};
}

void BM_GrayScottThroughRate(benchmark::State& state) {
  if (!grayScott().program) return state.SkipWithError(grayScott().error.c_str());
  const int side = static_cast<int>(state.range(0));
  for (auto _ : state) {
    state.PauseTiming();
    World world(grayScott().program, kBenchWorld);
    if (world.rootPool().size() != static_cast<size_t>(side) * side) return state.SkipWithError("not the 64 x 64 grid");
    state.ResumeTiming();
    world.advanceTo(kGrayScottSteps, 1.0);
  }
  state.counters["updates/s"] = benchmark::Counter(static_cast<double>(side) * side * kGrayScottSteps,
                                                   benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_GrayScottThroughRate)->Arg(64)->Unit(benchmark::kMillisecond);

// The same equations and classic RK4 by hand over flat arrays of u and v, from the
// model's own initial state; the result must agree with the engine's to rounding.
void grayScottRates(int side, const std::vector<double>& u, const std::vector<double>& v, std::vector<double>& du,
                    std::vector<double>& dv) {
  constexpr double Du = 0.2, Dv = 0.1, F = 0.0367, K = 0.0649;
  for (int y = 0; y < side; ++y) {
    const int up = (y + side - 1) % side * side, down = (y + 1) % side * side, row = y * side;
    for (int x = 0; x < side; ++x) {
      const int left = row + (x + side - 1) % side, right = row + (x + 1) % side, i = row + x;
      const double uvv = u[i] * v[i] * v[i];
      du[i] = Du * (u[up + x] + u[left] + u[right] + u[down + x] - 4 * u[i]) - uvv + F * (1 - u[i]);
      dv[i] = Dv * (v[up + x] + v[left] + v[right] + v[down + x] - 4 * v[i]) + uvv - (F + K) * v[i];
    }
  }
}

void BM_GrayScottHandWritten(benchmark::State& state) {
  if (!grayScott().program) return state.SkipWithError(grayScott().error.c_str());
  const int side = static_cast<int>(state.range(0));
  const size_t n = static_cast<size_t>(side) * side;
  std::vector<double> initial;
  {
    World world(grayScott().program, kBenchWorld);
    const auto arena = world.rootPool().stateArena();
    initial.assign(arena.begin(), arena.end());
  }
  if (initial.size() != 2 * n) return state.SkipWithError("not the 64 x 64 grid of u and v");
  std::vector<double> u(n), v(n), tu(n), tv(n), su(n), sv(n), ku(n), kv(n);
  for (auto _ : state) {
    for (size_t i = 0; i < n; ++i) u[i] = initial[2 * i], v[i] = initial[2 * i + 1];
    for (int step = 0; step < kGrayScottSteps; ++step) {
      constexpr double dt = 1.0;
      // k1 .. k4 summed into su, sv as they come; tu, tv hold each stage's input.
      grayScottRates(side, u, v, ku, kv);
      for (size_t i = 0; i < n; ++i) {
        su[i] = ku[i], sv[i] = kv[i];
        tu[i] = u[i] + 0.5 * dt * ku[i], tv[i] = v[i] + 0.5 * dt * kv[i];
      }
      grayScottRates(side, tu, tv, ku, kv);
      for (size_t i = 0; i < n; ++i) {
        su[i] += 2 * ku[i], sv[i] += 2 * kv[i];
        tu[i] = u[i] + 0.5 * dt * ku[i], tv[i] = v[i] + 0.5 * dt * kv[i];
      }
      grayScottRates(side, tu, tv, ku, kv);
      for (size_t i = 0; i < n; ++i) {
        su[i] += 2 * ku[i], sv[i] += 2 * kv[i];
        tu[i] = u[i] + dt * ku[i], tv[i] = v[i] + dt * kv[i];
      }
      grayScottRates(side, tu, tv, ku, kv);
      for (size_t i = 0; i < n; ++i) {
        u[i] += dt / 6 * (su[i] + ku[i]);
        v[i] += dt / 6 * (sv[i] + kv[i]);
      }
    }
    benchmark::DoNotOptimize(u.data());
    benchmark::DoNotOptimize(v.data());
  }
  const std::vector<double> engine = grayScottThroughWorld();
  for (size_t i = 0; i < n; ++i)
    if (std::abs(engine[2 * i] - u[i]) > 1e-6 || std::abs(engine[2 * i + 1] - v[i]) > 1e-6)
      return state.SkipWithError("the hand-written RK4 disagrees with the engine");
  state.counters["updates/s"] =
      benchmark::Counter(static_cast<double>(n) * kGrayScottSteps, benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_GrayScottHandWritten)->Arg(64)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace ontogen::bench
