// Final modules per second, from the axiom: each iteration grows a fresh world from the
// axiom to generation n of a context-free L-system, and the rate is the final word's
// size over the time of the whole derivation (the convention lpfg's figures use). The
// result is checked in every iteration, so a broken engine reports an error, not a time.
//
// Untimed productions: every module lives one time unit, so t = n is generation n.

#include <benchmark/benchmark.h>

#include <bit>
#include <chrono>
#include <cstdint>
#include <string>

#include "bench/bench_support.h"
#include "core/world.h"
#include "pools/mix_key.h"

namespace ontogen::bench {
namespace {

uint64_t power(uint64_t base, int exponent) {
  uint64_t result = 1;
  for (int i = 0; i < exponent; ++i) result *= base;
  return result;
}

/// Checks the developed word; returns an empty string when it is right.
using WordCheck = std::string (*)(const Program& program, const World& world, int n);

// Grows `program` from its axiom to generation n once per iteration, on the threads of
// the second argument (the context-free pass of core/parallel_rewrite.h).
void deriveFromAxiom(benchmark::State& state, const Compiled& compiled, uint64_t expectedSize, WordCheck check) {
  if (!compiled.program) {
    state.SkipWithError(compiled.error.c_str());
    return;
  }
  const int n = static_cast<int>(state.range(0));
  WorldDef def = kBenchWorld;
  def.threads = static_cast<unsigned>(state.range(1));
  FirstAndWarm firstAndWarm;
  double replaySeconds = 0;
  for (auto _ : state) {
    const double start = processSeconds();
    World world(compiled.program, def);
    world.advanceTo(n, 1.0);
    firstAndWarm.add(processSeconds() - start);
    if (world.rootPool().size() != expectedSize) {
      state.SkipWithError(
          ("word of " + std::to_string(world.rootPool().size()) + " modules, expected " + std::to_string(expectedSize))
              .c_str());
      return;
    }
    // The content check reads the whole word: keep it out of the measured time. A word
    // grown without its ids (docs/COMPACT_WORDS.md, "Words without ids") makes them again
    // when first read: that replay is reported apart, as replay_ms.
    state.PauseTiming();
    const auto replayStart = std::chrono::steady_clock::now();
    world.rootPool().ensureIds();
    replaySeconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - replayStart).count();
    std::string error = check(*compiled.program, world, n);
    if (!error.empty()) {
      state.SkipWithError(error.c_str());
      return;
    }
    state.ResumeTiming();  // the world's destruction is part of the run, as for the hand-written one
  }
  firstAndWarm.report(state);
  state.counters["replay_ms"] = 1e3 * replaySeconds / static_cast<double>(state.iterations());
  state.counters["modules"] = static_cast<double>(expectedSize);
  state.counters["modules/s"] = benchmark::Counter(
      static_cast<double>(expectedSize) * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

// ---- Koch: F -> F+F-F-F+F ----
// Each F becomes 5 F and 4 turns, turns stay: F_n = 5^n and the length grows by 8 F_{n-1},
// so |w_n| = 1 + 8 (5^n - 1) / 4 = 2 * 5^n - 1 (19,531,249 at n = 10).

const char* kKochText = R"(lsystem koch {
  axiom F
  F -> F + F - F - F + F
})";

std::string checkKoch(const Program& program, const World& world, int n) {
  auto f = masterOf(program, "F");
  if (!f) return "no module F";
  uint64_t count = 0;
  for (CellCursor cell = world.rootPool().cursor(); !cell.done(); cell.next()) count += cell.master() == *f;
  if (count != power(5, n)) return "Koch: " + std::to_string(count) + " F, expected 5^n";
  return {};
}

void BM_KochFromAxiom(benchmark::State& state) {
  static const Compiled compiled = compileText("koch.cell", kKochText);
  const int n = static_cast<int>(state.range(0));
  deriveFromAxiom(state, compiled, 2 * power(5, n) - 1, checkKoch);
}
BENCHMARK(BM_KochFromAxiom)->Args({10, 1})->Args({10, 2})->Unit(benchmark::kMillisecond)->Iterations(3)->UseRealTime();

// ---- Thue-Morse: a -> ab, b -> ba ----
// |w_n| = 2^n, and symbol i is b exactly when i has an odd number of ones.

const char* kThueMorseText = R"(lsystem thueMorse {
  axiom a
  a -> a b
  b -> b a
})";

std::string checkThueMorse(const Program& program, const World& world, int) {
  auto a = masterOf(program, "a");
  auto b = masterOf(program, "b");
  if (!a || !b) return "no module a or b";
  for (CellCursor cell = world.rootPool().cursor(); !cell.done(); cell.next())
    if (cell.master() != (std::popcount(cell.index()) % 2 ? *b : *a))
      return "Thue-Morse: wrong symbol at " + std::to_string(cell.index());
  return {};
}

void BM_ThueMorseFromAxiom(benchmark::State& state) {
  static const Compiled compiled = compileText("thue_morse.cell", kThueMorseText);
  const int n = static_cast<int>(state.range(0));
  deriveFromAxiom(state, compiled, power(2, n), checkThueMorse);
}
BENCHMARK(BM_ThueMorseFromAxiom)->Args({24, 1})->Args({24, 2})->Unit(benchmark::kMillisecond)->Iterations(3)->UseRealTime();

// ---- A stochastic plant (ABOP Fig. 1.27): each F draws one of three bracketed rules ----
// The word depends on the draws, so it is checked against the same program grown once
// by the records' serial pass (WorldDef::rewriteBySlices off), an independent path:
// size, and a hash of every module's label and id.

const char* kStochasticPlantText = R"(lsystem plant {
  axiom F
  F -> F [ + F ] F [ - F ] F : 0.33
  F -> F [ + F ] F : 0.33
  F -> F [ - F ] F : 0.34
})";

uint64_t hashOfWord(const World& world) {
  uint64_t hash = 0;
  for (CellCursor cell = world.rootPool().cursor(); !cell.done(); cell.next())
    hash = mixKey(hash, mixKey(cell.master(), cell.id()));
  return hash;
}

struct Reference {
  uint64_t size = 0, hash = 0;
};
const Reference& stochasticPlantReference(const Compiled& compiled, int n) {
  static const Reference reference = [&] {
    WorldDef def = kBenchWorld;
    def.rewriteBySlices = false;
    World world(compiled.program, def);
    world.advanceTo(n, 1.0);
    return Reference{world.rootPool().size(), hashOfWord(world)};
  }();
  return reference;
}

const Reference* stochasticReference = nullptr;
std::string checkStochasticPlant(const Program&, const World& world, int) {
  if (hashOfWord(world) != stochasticReference->hash) return "stochastic plant: not the serial pass's word";
  return {};
}

void BM_StochasticPlantFromAxiom(benchmark::State& state) {
  static const Compiled compiled = compileText("stochastic_plant.cell", kStochasticPlantText);
  const int n = static_cast<int>(state.range(0));
  if (!compiled.program) {
    state.SkipWithError(compiled.error.c_str());
    return;
  }
  stochasticReference = &stochasticPlantReference(compiled, n);
  deriveFromAxiom(state, compiled, stochasticReference->size, checkStochasticPlant);
}
BENCHMARK(BM_StochasticPlantFromAxiom)
    ->Args({11, 1})
    ->Args({11, 2})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3)
    ->UseRealTime();

// ---- Parametric: A(x) -> A(x+1) B(x*0.5), B(y) -> B(y+1) B(y*0.5) ----
// |w_n| = 2^n: one A, whose parameter is 1 + n, then 2^n - 1 B.

const char* kParametricText = R"(lsystem parametric {
  axiom A(1)
  A(x) -> A(x + 1) B(x * 0.5)
  B(y) -> B(y + 1) B(y * 0.5)
})";

std::string checkParametric(const Program& program, const World& world, int n) {
  auto a = masterOf(program, "A");
  auto b = masterOf(program, "B");
  if (!a || !b) return "no module A or B";
  const Pool& pool = world.rootPool();
  const CellView first = pool.cellAt(0);
  if (first.master != *a || *first.state != 1.0 + n) return "parametric: the first module is not A(1 + n)";
  CellCursor cell = pool.cursor();
  for (cell.next(); !cell.done(); cell.next())
    if (cell.master() != *b) return "parametric: module " + std::to_string(cell.index()) + " is not B";
  return {};
}

void BM_ParametricFromAxiom(benchmark::State& state) {
  static const Compiled compiled = compileText("parametric.cell", kParametricText);
  const int n = static_cast<int>(state.range(0));
  deriveFromAxiom(state, compiled, power(2, n), checkParametric);
}
BENCHMARK(BM_ParametricFromAxiom)->Args({20, 1})->Args({20, 2})->Unit(benchmark::kMillisecond)->Iterations(10)->UseRealTime();

}  // namespace
}  // namespace ontogen::bench
