// Koch's curve grown in the compact word of pools/compact_word.h alone, without the
// engine around it: what the linear pool's storage costs once the development writes it
// (docs/COMPACT_WORDS.md, slices 4 and 5), beside BM_KochHandWritten's bytes and
// BM_KochFromAxiom's engine. Each iteration grows the word from the axiom as the engine
// does: an F expiring at generation t makes a run of nine born at t, keyed by
// mixKey(its id, t); a sign never expires and is copied with its key and birth index.

#include <benchmark/benchmark.h>

#include <cstdint>
#include <vector>

#include "bench/bench_support.h"
#include "core/parallel_for.h"
#include "core/parallel_rewrite.h"
#include "core/world.h"
#include "pools/compact_word.h"
#include "pools/large_block_cache.h"

namespace ontogen::bench {
namespace {

constexpr uint32_t kF = 0;
constexpr uint32_t kProduction[] = {0, 1, 0, 2, 0, 2, 0, 1, 0};  // F+F-F-F+F; 1 is +, 2 is -

template <class Writer>
void rewriteKoch(const CompactWord& word, size_t begin, size_t end, double when, Writer& writer) {
  for (CompactWordCursor cell(word, begin); !cell.done() && cell.index() < end; cell.next()) {
    if (cell.master() != kF) {
      writer.appendCopy(cell.master(), cell.key(), cell.birthIndex());
      continue;
    }
    const uint64_t lineage = mixKey(cell.id(), keyOf(when));
    for (uint32_t k = 1; k <= 9; ++k) writer.append(kProduction[k - 1], IdKey{lineage, k}, when);
  }
}

// The two writers under one interface: the serial one, and a slice.
struct SerialWriter {
  CompactWord& word;
  void append(uint32_t label, IdKey key, double birth) { word.append(label, key, birth, nullptr); }
  void appendCopy(uint32_t label, IdKey key, uint32_t birthIndex) { word.append(label, key, birthIndex, nullptr); }
};
struct SliceWriter {
  CompactWord::Slice& slice;
  void append(uint32_t label, IdKey key, double birth) { slice.append(label, key, birth, nullptr); }
  void appendCopy(uint32_t label, IdKey key, uint32_t birthIndex) { slice.appendCopy(label, key, birthIndex, nullptr); }
};

// Arguments: n, then T: 0 the serial writer, else T threads writing 4 slices each.
void BM_KochCompactWord(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const unsigned threads = static_cast<unsigned>(state.range(1));
  uint64_t fives = 1;
  for (int i = 0; i < n; ++i) fives *= 5;
  const uint64_t expected = 2 * fives - 1;
  double bytesPerModule = 0;
  std::vector<CompactWord::Slice> slices;  // kept: their buffers of runs are reused
  FirstAndWarm firstAndWarm;
  for (auto _ : state) {
    const double start = processSeconds();
    CompactWord word({0, 0, 0}), next({0, 0, 0});
    word.append(kF, IdKey{mixKey(1, 0), 0}, 0.0, nullptr);
    for (int generation = 1; generation <= n; ++generation) {
      const double when = generation;
      next.clearWithBirthsOf(word);
      if (threads == 0) {
        SerialWriter writer{next};
        rewriteKoch(word, 0, word.size(), when, writer);
      } else {
        const size_t count = size_t{threads} * 4;
        slices.resize(count, CompactWord::Slice(word));
        for (CompactWord::Slice& slice : slices) slice.restart(word);
        auto pass = [&](size_t begin, size_t end, unsigned) {
          for (size_t s = begin; s < end; ++s) {
            SliceWriter writer{slices[s]};
            rewriteKoch(word, word.size() * s / count, word.size() * (s + 1) / count, when, writer);
            slices[s].finish();
          }
        };
        parallelFor(count, threads, pass, 1);
        next.beginSlices(slices);
        parallelFor(count, threads, pass, 1);
        next.endSlices(slices);
      }
      next.finish();
      std::swap(word, next);
    }
    firstAndWarm.add(processSeconds() - start);
    benchmark::DoNotOptimize(word.labels8().data());
    if (word.size() != expected || word.label(0) != kF || word.label(1) != 1) {
      state.SkipWithError("compact Koch: wrong word");
      return;
    }
    bytesPerModule = static_cast<double>(word.bytes()) / static_cast<double>(word.size());
  }
  state.counters["modules/s"] = benchmark::Counter(static_cast<double>(expected) * static_cast<double>(state.iterations()),
                                                   benchmark::Counter::kIsRate);
  state.counters["bytes/module"] = bytesPerModule;
  firstAndWarm.report(state);
}
BENCHMARK(BM_KochCompactWord)
    ->Args({10, 0})
    ->Args({10, 1})
    ->Args({10, 2})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3)
    ->UseRealTime();

// The same growth through the engine's pass on compact words (ParallelRewrite::
// rewriteCompact): the rule chosen from the program, lifetimes, lineage keys and ids as
// the engine computes them, from the engine's axiom. Argument: n, then T threads.
void BM_KochCompactRewrite(benchmark::State& state) {
  static const Compiled compiled = compileText("koch.cell", "lsystem koch {\n  axiom F\n  F -> F + F - F - F + F\n}\n");
  if (!compiled.program) {
    state.SkipWithError(compiled.error.c_str());
    return;
  }
  const Program& program = *compiled.program;
  const int n = static_cast<int>(state.range(0));
  const unsigned threads = static_cast<unsigned>(state.range(1));
  uint64_t fives = 1;
  for (int i = 0; i < n; ++i) fives *= 5;
  std::vector<uint32_t> stateCounts;
  for (const MasterCell& master : program.masters) stateCounts.push_back(master.stateCount());
  ParallelRewrite rewrite(program, program.systems[program.root]);
  const World axiom(compiled.program, kBenchWorld);
  FirstAndWarm firstAndWarm;
  uint64_t freshBlocks = 0;
  for (auto _ : state) {
    const double start = processSeconds();
    const uint64_t freshBefore = largeBlockCacheStats().fresh;
    CompactWord word(stateCounts), next(stateCounts);
    for (CellCursor cell = axiom.rootPool().cursor(); !cell.done(); cell.next())
      word.append(cell.master(), IdKey::whole(cell.id()), cell.birth(), nullptr);
    for (int generation = 1; generation <= n; ++generation) {
      rewrite.rewriteCompact(word, generation, 0, threads, next);
      std::swap(word, next);
    }
    firstAndWarm.add(processSeconds() - start);
    freshBlocks = largeBlockCacheStats().fresh - freshBefore;  // the last world's
    if (word.size() != 2 * fives - 1) {
      state.SkipWithError("compact Koch through the engine: wrong word");
      return;
    }
  }
  state.counters["modules/s"] = benchmark::Counter(static_cast<double>(2 * fives - 1) * static_cast<double>(state.iterations()),
                                                   benchmark::Counter::kIsRate);
  firstAndWarm.report(state);
  state.counters["fresh blocks"] = static_cast<double>(freshBlocks);
}
BENCHMARK(BM_KochCompactRewrite)->Args({10, 1})->Args({10, 2})->Unit(benchmark::kMillisecond)->Iterations(3)->UseRealTime();

}  // namespace
}  // namespace ontogen::bench
