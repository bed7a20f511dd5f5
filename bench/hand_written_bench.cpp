// Koch's curve rewritten by hand, the baseline for the engine's modules per second:
// a std::vector<char> rewritten generation by generation into a second buffer, both
// reserved once for the final size (a competent programmer knows |w_n| = 2 * 5^n - 1).
// Same n, same counter and same check as BM_KochFromAxiom in derivation_bench.cpp.

#include <benchmark/benchmark.h>

#include <cstdint>
#include <string_view>
#include <vector>

namespace ontogen::bench {
namespace {

constexpr std::string_view kKochSuccessor = "F+F-F-F+F";

uint64_t kochLength(int n) {
  uint64_t fives = 1;
  for (int i = 0; i < n; ++i) fives *= 5;
  return 2 * fives - 1;
}

void BM_KochHandWritten(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const uint64_t expected = kochLength(n);
  for (auto _ : state) {
    std::vector<char> word;
    std::vector<char> next;
    word.reserve(expected);
    next.reserve(expected);
    word.push_back('F');
    for (int generation = 0; generation < n; ++generation) {
      next.clear();
      for (char symbol : word) {
        if (symbol == 'F')
          next.insert(next.end(), kKochSuccessor.begin(), kKochSuccessor.end());
        else
          next.push_back(symbol);
      }
      word.swap(next);
    }
    benchmark::DoNotOptimize(word.data());
    state.PauseTiming();
    uint64_t segments = 0;
    for (char symbol : word) segments += symbol == 'F';
    if (word.size() != expected || 2 * segments - 1 != expected) {
      state.SkipWithError("hand-written Koch: wrong word");
      return;
    }
    state.ResumeTiming();
  }
  state.counters["modules"] = static_cast<double>(expected);
  state.counters["modules/s"] = benchmark::Counter(
      static_cast<double>(expected) * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_KochHandWritten)->Arg(10)->Unit(benchmark::kMillisecond)->Iterations(5)->UseRealTime();

}  // namespace
}  // namespace ontogen::bench
