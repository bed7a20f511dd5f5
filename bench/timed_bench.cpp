// Timed development: the piston and flywheel of paper 000 (models/piston.cell) developed
// over whole periods with the animation step of 0.04 s. Its word is 12 modules, so this
// measures the cost of a step and of a terminal-age event, not of the word's size. And a
// chain of generations within one step.

#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>

#include "bench/bench_support.h"
#include "core/world.h"

namespace ontogen::bench {
namespace {

constexpr double kPeriod = 4;             // ρ of the model, seconds
constexpr double kBuildAge = 0.04;        // E: p1 builds the mechanism at this time, seconds
constexpr double kStep = 0.04;            // seconds, the model's #dt (25 frames per second)
constexpr size_t kMechanismModules = 12;  // the word p1 builds: mov ! cC bend ! cC turn f + [ disc ]

void BM_PistonPeriods(benchmark::State& state) {
  static const Compiled compiled = compileModel("piston.cell");
  if (!compiled.program) {
    state.SkipWithError(compiled.error.c_str());
    return;
  }
  const int periods = static_cast<int>(state.range(0));
  const double until = periods * kPeriod;
  const uint64_t expectedSteps = static_cast<uint64_t>(std::llround(until / kStep));
  // p1 once at E, then mov, bend and turn renew at E + kρ for k = 1 .. periods - 1.
  const uint64_t expectedEvents = 1 + 3 * static_cast<uint64_t>(std::floor((until - kBuildAge) / kPeriod));
  uint64_t steps = 0;
  uint64_t events = 0;
  for (auto _ : state) {
    World world(compiled.program, kBenchWorld);
    world.advanceTo(until, kStep);
    const WorldStats& stats = world.stats();
    if (stats.steps != expectedSteps || stats.events != expectedEvents ||
        world.rootPool().size() != kMechanismModules) {
      state.SkipWithError(("piston: " + std::to_string(stats.steps) + " steps, " + std::to_string(stats.events) +
                           " events, " + std::to_string(world.rootPool().size()) + " modules; expected " +
                           std::to_string(expectedSteps) + ", " + std::to_string(expectedEvents) + ", " +
                           std::to_string(kMechanismModules))
                              .c_str());
      return;
    }
    steps += stats.steps;
    events += stats.events;
  }
  state.counters["steps/s"] = benchmark::Counter(static_cast<double>(steps), benchmark::Counter::kIsRate);
  state.counters["events/s"] = benchmark::Counter(static_cast<double>(events), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_PistonPeriods)->Arg(100)->Unit(benchmark::kMillisecond)->UseRealTime();

// A chain of 2^n generations within one step of 1 s: a module of lifetime 2^-n s that
// writes its successor, walked by the table alone and written without ids (the replay of
// its ids keeps every instant). Linear in the chain: 2^n rewrites of a word of one module.
void BM_ChainWithinOneStep(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  char lifetime[32];
  std::snprintf(lifetime, sizeof lifetime, "%.17g", std::ldexp(1.0, -n));  // exact: a power of two
  const Compiled compiled =
      compileText("chain.cell", std::string("cell A { lifetime ") + lifetime +
                                    "; rules { terminal: -> A; } }\nsystem s { pool linear; axiom A; }\n");
  if (!compiled.program) {
    state.SkipWithError(compiled.error.c_str());
    return;
  }
  const uint64_t generations = uint64_t{1} << n;
  for (auto _ : state) {
    World world(compiled.program, kBenchWorld);
    world.advanceTo(1, 1);
    if (world.stats().events != generations || world.rootPool().size() != 1) {
      state.SkipWithError(
          ("chain: " + std::to_string(world.stats().events) + " events; expected " + std::to_string(generations))
              .c_str());
      return;
    }
  }
  state.counters["generations/s"] =
      benchmark::Counter(static_cast<double>(generations * state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_ChainWithinOneStep)->Arg(14)->Arg(16)->Arg(18)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace ontogen::bench
