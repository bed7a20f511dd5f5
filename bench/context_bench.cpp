// Context-sensitive rewriting: a signal travels along a word of 100,000 modules (ABOP
// 1.8): `b < a -> b` and `b -> a`, one `b` followed by 99,999 `a`. Every step rewrites
// every module (the `a` without `b` on their left renew themselves), so the rate is
// rewrites per second = modules x steps / time. The word is checked after the run: one
// `b`, at position `steps`.

#include <benchmark/benchmark.h>

#include <cstdint>
#include <string>

#include "bench/bench_support.h"
#include "core/world.h"

namespace ontogen::bench {
namespace {

constexpr int kSignalModules = 100'000;

std::string signalText(int modules) {
  std::string text = "lsystem signal {\n  axiom b";
  text.reserve(text.size() + 2 * static_cast<size_t>(modules) + 64);
  for (int i = 1; i < modules; ++i) text += " a";
  text += "\n  b < a -> b\n  b -> a\n}\n";
  return text;
}

std::string checkSignal(const Program& program, const World& world, int steps) {
  auto b = masterOf(program, "b");
  if (!b) return "no module b";
  const Pool& pool = world.rootPool();
  if (pool.size() != kSignalModules)
    return "signal: word of " + std::to_string(pool.size()) + " modules, expected " + std::to_string(kSignalModules);
  uint64_t count = 0;
  for (CellCursor cell = pool.cursor(); !cell.done(); cell.next()) count += cell.master() == *b;
  if (count != 1 || pool.cellAt(static_cast<size_t>(steps)).master != *b)
    return "signal: expected one b at position " + std::to_string(steps);
  return {};
}

void BM_ContextSignal(benchmark::State& state) {
  static const Compiled compiled = compileText("signal.cell", signalText(kSignalModules));
  if (!compiled.program) {
    state.SkipWithError(compiled.error.c_str());
    return;
  }
  const int steps = static_cast<int>(state.range(0));
  WorldDef def = kBenchWorld;
  def.threads = static_cast<unsigned>(state.range(1));  // 2: the pass of core/parallel_rewrite.h
  for (auto _ : state) {
    World world(compiled.program, def);
    world.advanceTo(steps, 1.0);
    state.PauseTiming();
    std::string error = checkSignal(*compiled.program, world, steps);
    if (!error.empty()) {
      state.SkipWithError(error.c_str());
      return;
    }
    state.ResumeTiming();
  }
  const double rewrites = static_cast<double>(kSignalModules) * steps * static_cast<double>(state.iterations());
  state.counters["rewrites/s"] = benchmark::Counter(rewrites, benchmark::Counter::kIsRate);
}
BENCHMARK(BM_ContextSignal)->Args({1000, 1})->Args({1000, 2})->Unit(benchmark::kMillisecond)->Iterations(1)->UseRealTime();

}  // namespace
}  // namespace ontogen::bench
