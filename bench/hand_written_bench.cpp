// The derivation benchmarks written by hand, the baselines for the engine's rates: a
// word rewritten generation by generation into a second buffer, both reserved for the
// final size (a competent programmer knows |w_n|). Same n, same counters and same checks
// as derivation_bench.cpp and context_bench.cpp: Koch and Thue-Morse as bytes, the
// parametric system as a label byte and a double per module, the signal as bytes.
//
// The buffers are made and touched once, before the timed loop, and reused by every
// iteration: the baseline measures the rewriting itself on warm memory. Made afresh in
// each iteration, their time depended on what the process had freed before (glibc's
// malloc serves a large block from memory it already mapped once it has freed large
// ones): Thue-Morse's took 88 ms alone and 21 ms after the engine's benchmarks, the
// parametric one's 77 ms and 2.3 ms. The engine's later worlds reuse memory too (the
// large block cache); what its first world pays for fresh pages is its first/warm.

#include <benchmark/benchmark.h>
#include <sys/mman.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstring>
#include <new>
#include <string_view>
#include <utility>
#include <vector>

namespace ontogen::bench {
namespace {

constexpr std::string_view kKochSuccessor = "F+F-F-F+F";

// An empty vector with room for `size` elements, every page of which is already written.
template <class T>
std::vector<T> warmBuffer(size_t size) {
  std::vector<T> buffer(size);
  benchmark::DoNotOptimize(buffer.data());
  buffer.clear();
  return buffer;
}

uint64_t kochLength(int n) {
  uint64_t fives = 1;
  for (int i = 0; i < n; ++i) fives *= 5;
  return 2 * fives - 1;
}

void BM_KochHandWritten(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const uint64_t expected = kochLength(n);
  std::vector<char> word = warmBuffer<char>(expected), next = warmBuffer<char>(expected);
  for (auto _ : state) {
    word.clear();
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

// Bytes mapped from the kernel, fresh, and marked for huge pages from 2 MiB on, as the
// large block cache maps a block it has not got (pools/large_block_cache.h); unmapped when
// dropped.
class FreshPages {
 public:
  explicit FreshPages(size_t bytes) : bytes_(std::max<size_t>(bytes, 1)) {
    void* block = mmap(nullptr, bytes_, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (block == MAP_FAILED) throw std::bad_alloc();
    if (bytes_ >= (size_t{2} << 20)) madvise(block, bytes_, MADV_HUGEPAGE);
    data_ = static_cast<char*>(block);
  }
  FreshPages(FreshPages&& other) noexcept
      : data_(std::exchange(other.data_, nullptr)), bytes_(std::exchange(other.bytes_, 0)) {}
  FreshPages& operator=(FreshPages&& other) noexcept {
    std::swap(data_, other.data_);
    std::swap(bytes_, other.bytes_);
    return *this;
  }
  ~FreshPages() {
    if (data_) munmap(data_, bytes_);
  }
  char* data() const { return data_; }

 private:
  char* data_ = nullptr;
  size_t bytes_ = 0;
};

// The hand-written Koch again, each generation written into pages fresh from the kernel,
// sized for it, the word before unmapped: every iteration pays for its pages what a
// process's first world pays at the least (it has no memory to reuse). Beside
// BM_KochHandWritten, its time less that one's is the price of the pages alone, to which
// the engine's first/warm is compared (bench/README.md).
void BM_KochHandWrittenFreshPages(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const uint64_t expected = kochLength(n);
  for (auto _ : state) {
    FreshPages word(1);
    word.data()[0] = 'F';
    uint64_t size = 1, segments = 1;
    for (int generation = 0; generation < n; ++generation) {
      FreshPages next(size + 8 * segments);
      char* out = next.data();
      for (const char* symbol = word.data(); symbol != word.data() + size; ++symbol) {
        if (*symbol == 'F') {
          std::memcpy(out, kKochSuccessor.data(), kKochSuccessor.size());
          out += kKochSuccessor.size();
        } else {
          *out++ = *symbol;
        }
      }
      size = static_cast<uint64_t>(out - next.data());
      segments *= 5;
      word = std::move(next);
    }
    benchmark::DoNotOptimize(word.data());
    state.PauseTiming();
    uint64_t counted = 0;
    for (uint64_t i = 0; i < size; ++i) counted += word.data()[i] == 'F';
    if (size != expected || counted != segments) {
      state.SkipWithError("hand-written Koch in fresh pages: wrong word");
      return;
    }
    state.ResumeTiming();
  }
  state.counters["modules"] = static_cast<double>(expected);
}
BENCHMARK(BM_KochHandWrittenFreshPages)->Arg(10)->Unit(benchmark::kMillisecond)->Iterations(5)->UseRealTime();

// a -> ab, b -> ba to n = 24: 2^n bytes, symbol i is b iff popcount(i) is odd.
void BM_ThueMorseHandWritten(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const uint64_t expected = uint64_t{1} << n;
  std::vector<char> word = warmBuffer<char>(expected), next = warmBuffer<char>(expected);
  for (auto _ : state) {
    word.clear();
    word.push_back('a');
    for (int generation = 0; generation < n; ++generation) {
      next.clear();
      for (char symbol : word) {
        next.push_back(symbol);
        next.push_back(symbol == 'a' ? 'b' : 'a');
      }
      word.swap(next);
    }
    benchmark::DoNotOptimize(word.data());
    state.PauseTiming();
    for (uint64_t i = 0; i < word.size(); ++i)
      if (word[i] != (std::popcount(i) % 2 ? 'b' : 'a')) {
        state.SkipWithError("hand-written Thue-Morse: wrong word");
        return;
      }
    state.ResumeTiming();
  }
  state.counters["modules/s"] = benchmark::Counter(
      static_cast<double>(expected) * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_ThueMorseHandWritten)->Arg(24)->Unit(benchmark::kMillisecond)->Iterations(3)->UseRealTime();

// ABOP Fig. 1.27's stochastic plant as bytes: each F draws one of its three rules (chances
// 0.33, 0.33, 0.34) from a SplitMix64 stream of its own (the generation and its place in
// the word), as the engine draws from each cell's stream. The draws differ from the
// engine's, so the word does too; its size is what the rate counts.
void BM_StochasticPlantHandWritten(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  constexpr std::string_view kRules[] = {"F[+F]F[-F]F", "F[+F]F", "F[-F]F"};
  std::vector<char> word = warmBuffer<char>(size_t{24} << 20), next = warmBuffer<char>(size_t{24} << 20);
  uint64_t size = 0;
  for (auto _ : state) {
    word.clear();
    word.push_back('F');
    for (int generation = 0; generation < n; ++generation) {
      next.clear();
      for (size_t i = 0; i < word.size(); ++i) {
        if (word[i] != 'F') {
          next.push_back(word[i]);
          continue;
        }
        uint64_t z = (uint64_t(generation) << 40 ^ i) + 0x9E3779B97F4A7C15ull;
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        const double x = static_cast<double>((z ^ (z >> 31)) >> 11) * 0x1.0p-53;
        const std::string_view rule = kRules[x < 0.33 ? 0 : x < 0.66 ? 1 : 2];
        next.insert(next.end(), rule.begin(), rule.end());
      }
      word.swap(next);
    }
    benchmark::DoNotOptimize(word.data());
    size = word.size();
  }
  state.counters["modules"] = static_cast<double>(size);
  state.counters["modules/s"] = benchmark::Counter(static_cast<double>(size) * static_cast<double>(state.iterations()),
                                                   benchmark::Counter::kIsRate);
}
BENCHMARK(BM_StochasticPlantHandWritten)->Arg(11)->Unit(benchmark::kMillisecond)->Iterations(3)->UseRealTime();

// A(x) -> A(x + 1) B(x * 0.5), B(y) -> B(y + 1) B(y * 0.5) from A(1) to n = 20, with a
// label and a double per module: 2^n modules, A(1 + n) first.
void BM_ParametricHandWritten(benchmark::State& state) {
  struct Module {
    char label;
    double value;
  };
  const int n = static_cast<int>(state.range(0));
  const uint64_t expected = uint64_t{1} << n;
  std::vector<Module> word = warmBuffer<Module>(expected), next = warmBuffer<Module>(expected);
  for (auto _ : state) {
    word.clear();
    word.push_back({'A', 1.0});
    for (int generation = 0; generation < n; ++generation) {
      next.clear();
      for (const Module& module : word) {
        next.push_back({module.label, module.value + 1});
        next.push_back({'B', module.value * 0.5});
      }
      word.swap(next);
    }
    benchmark::DoNotOptimize(word.data());
    if (word.size() != expected || word[0].label != 'A' || word[0].value != 1.0 + n) {
      state.SkipWithError("hand-written parametric: wrong word");
      return;
    }
  }
  state.counters["modules/s"] = benchmark::Counter(
      static_cast<double>(expected) * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_ParametricHandWritten)->Arg(20)->Unit(benchmark::kMillisecond)->Iterations(10)->UseRealTime();

// b < a -> b, b -> a on b and 99,999 a, 1,000 steps, as bytes in two buffers.
void BM_ContextSignalHandWritten(benchmark::State& state) {
  constexpr size_t kModules = 100'000;
  const int steps = static_cast<int>(state.range(0));
  std::vector<char> word = warmBuffer<char>(kModules), next = warmBuffer<char>(kModules);
  for (auto _ : state) {
    word.assign(kModules, 'a');
    next.resize(kModules);
    word[0] = 'b';
    for (int step = 0; step < steps; ++step) {
      next[0] = word[0] == 'b' ? 'a' : word[0];
      for (size_t i = 1; i < kModules; ++i)
        next[i] = word[i] == 'b' ? 'a' : (word[i] == 'a' && word[i - 1] == 'b' ? 'b' : word[i]);
      word.swap(next);
    }
    benchmark::DoNotOptimize(word.data());
    if (word[static_cast<size_t>(steps)] != 'b') {
      state.SkipWithError("hand-written signal: the b is not at position steps");
      return;
    }
  }
  state.counters["rewrites/s"] = benchmark::Counter(
      static_cast<double>(kModules) * steps * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_ContextSignalHandWritten)->Arg(1000)->Unit(benchmark::kMillisecond)->Iterations(3)->UseRealTime();

}  // namespace
}  // namespace ontogen::bench
