// Writing a word: what `ontogen word` does after developing, as text (writeWordText), as
// JSON (WordJsonWriter) and as compact JSON (CompactWordJsonWriter, `--json=compact`), into
// a stream that counts and drops its bytes, so the figures do not measure a disk or a
// pipe. The baseline writes the same text of the same Koch word by hand, from a byte per
// module, through the same kind of buffer; the derive-and-write pair times what `ontogen
// word` does as a whole, derivation included.

#include <benchmark/benchmark.h>

#include <algorithm>
#include <ostream>
#include <sstream>
#include <streambuf>
#include <string>
#include <string_view>
#include <vector>

#include "bench/bench_support.h"
#include "core/word.h"
#include "core/world.h"
#include "interpreters/text/word_text.h"
#include "pools/large_block_cache.h"

namespace ontogen::bench {
namespace {

// A stream buffer that keeps only the number of bytes written to it.
class CountingBuffer final : public std::streambuf {
 public:
  size_t bytes = 0;

 protected:
  std::streamsize xsputn(const char*, std::streamsize count) override {
    bytes += static_cast<size_t>(count);
    return count;
  }
  int_type overflow(int_type c) override {
    if (c != traits_type::eof()) ++bytes;
    return c;
  }
};

const Compiled& koch() {
  static const Compiled compiled = compileModel("koch.cell");
  return compiled;
}

void report(benchmark::State& state, size_t modules, size_t bytes) {
  state.counters["modules"] = static_cast<double>(modules);
  state.counters["MB"] = static_cast<double>(bytes) / 1e6;
  state.counters["modules/s"] =
      benchmark::Counter(static_cast<double>(modules * state.iterations()), benchmark::Counter::kIsRate);
}

// Grows Koch to generation range(0) once, then in every iteration writes its word through
// `write(world, buffered)` into the counting stream. `sizeIsRight(modules, bytes)` checks
// what the last iteration wrote.
template <typename Write, typename Check>
void writeKochWord(benchmark::State& state, Write&& write, Check&& sizeIsRight) {
  if (!koch().program) return state.SkipWithError(koch().error.c_str());
  World world(koch().program, kBenchWorld);
  world.advanceTo(static_cast<double>(state.range(0)), 1.0);
  CountingBuffer counter;
  std::ostream out(&counter);
  for (auto _ : state) {
    counter.bytes = 0;
    BufferedOutput buffered(out);
    write(world, buffered);
    buffered.flush();
  }
  if (!sizeIsRight(world.rootPool().size(), counter.bytes)) return state.SkipWithError("wrong output size");
  report(state, world.rootPool().size(), counter.bytes);
}

void BM_KochWordText(benchmark::State& state) {
  writeKochWord(
      state,
      [](const World& world, BufferedOutput& buffered) { writeWordText(world, buffered, 6); },
      // 2 bytes a module ("F " or "+ "), less the last space.
      [](size_t modules, size_t bytes) { return bytes == 2 * modules - 1; });
}
BENCHMARK(BM_KochWordText)->Arg(8)->Unit(benchmark::kMillisecond);

void BM_KochWordJson(benchmark::State& state) {
  writeKochWord(
      state,
      [](const World& world, BufferedOutput& buffered) {
        WordJsonWriter writer(buffered);
        writer.begin();
        writer.beginTime(world.time(), true);
        visitWord(world, writer);
        writer.endTime();
        writer.end();
      },
      [](size_t modules, size_t bytes) { return bytes > 100 * modules; });  // a record of ~110 bytes each
}
BENCHMARK(BM_KochWordJson)->Arg(8)->Unit(benchmark::kMillisecond);

void BM_KochWordJsonCompact(benchmark::State& state) {
  writeKochWord(
      state,
      [](const World& world, BufferedOutput& buffered) {
        CompactWordJsonWriter writer(buffered);
        writer.begin();
        writer.beginTime(world.time(), true);
        writer.writeWord(world);
        writer.endTime();
        writer.end();
      },
      // 4 bytes a module ("F", or "+",), less the last comma, and the frame around them.
      [](size_t modules, size_t bytes) {
        return bytes == 4 * modules - 1 + std::string_view("{\"form\": \"compact\", \"times\": [\n  {\"t\": 8, \"cells\": []}\n]}\n").size();
      });
}
BENCHMARK(BM_KochWordJsonCompact)->Arg(8)->Unit(benchmark::kMillisecond);

// Giving Koch's word at generation range(0), grown without ids, its ids (the replay of
// core/table_replay.h that every reader of ids pays first): each iteration grows a fresh
// world, outside the timed region, then times Pool::ensureIds. Reports the replay's and
// the derivation's processor times (median over iterations) and their ratio, and the
// blocks the replay took fresh from the system rather than from the large block cache.
void BM_KochIdReplay(benchmark::State& state) {
  if (!koch().program) return state.SkipWithError(koch().error.c_str());
  const int n = static_cast<int>(state.range(0));
  std::vector<double> derivations, replays;
  uint64_t freshBlocks = 0;
  for (auto _ : state) {
    state.PauseTiming();
    {
      double start = processSeconds();
      World world(koch().program, kBenchWorld);
      world.advanceTo(n, 1.0);
      derivations.push_back(processSeconds() - start);
      const uint64_t fresh = largeBlockCacheStats().fresh;
      state.ResumeTiming();
      start = processSeconds();
      world.rootPool().ensureIds();
      replays.push_back(processSeconds() - start);
      state.PauseTiming();
      freshBlocks += largeBlockCacheStats().fresh - fresh;
      if (!world.rootPool().holdsIds()) return state.SkipWithError("no ids after the replay");
    }
    state.ResumeTiming();
  }
  auto median = [](std::vector<double> values) {
    std::sort(values.begin(), values.end());
    return values[values.size() / 2];
  };
  state.counters["derivation_ms"] = 1e3 * median(derivations);
  state.counters["replay_ms"] = 1e3 * median(replays);
  state.counters["replay/derivation"] = median(replays) / median(derivations);
  state.counters["fresh_blocks"] = static_cast<double>(freshBlocks) / static_cast<double>(state.iterations());
}
BENCHMARK(BM_KochIdReplay)->Arg(10)->Unit(benchmark::kMillisecond)->Iterations(5);

// Koch's word derived by hand, a byte per module, both words reserved for the final size.
std::vector<char> kochByHand(int n) {
  size_t modules = 1;
  for (int i = 0; i < n; ++i) modules = modules * 5 + 4;  // 5 F and 4 turns a former F
  std::vector<char> word{'F'}, next;
  word.reserve(modules);
  next.reserve(modules);
  for (int i = 0; i < n; ++i) {
    next.clear();
    for (char c : word) {
      if (c == 'F')
        for (char s : {'F', '+', 'F', '-', 'F', '-', 'F', '+', 'F'}) next.push_back(s);
      else
        next.push_back(c);
    }
    word.swap(next);
  }
  return word;
}

// The word as symbols separated by spaces, through a 64 KiB buffer.
void writeByHand(const std::vector<char>& word, std::ostream& out) {
  std::string buffer;
  buffer.reserve((size_t{1} << 16) + 16);
  for (size_t i = 0; i < word.size(); ++i) {
    if (i) buffer += ' ';
    buffer += word[i];
    if (buffer.size() >= (size_t{1} << 16)) {
      out.write(buffer.data(), static_cast<std::streamsize>(buffer.size()));
      buffer.clear();
    }
  }
  out.write(buffer.data(), static_cast<std::streamsize>(buffer.size()));
}

// Whether the hand-written text is the engine's, byte for byte.
bool sameTextAsTheEngine(const std::vector<char>& word, int n) {
  World world(koch().program, kBenchWorld);
  world.advanceTo(n, 1.0);
  std::ostringstream engine, byHand;
  {
    BufferedOutput buffered(engine);
    writeWordText(world, buffered, 6);
  }
  writeByHand(word, byHand);
  return engine.str() == byHand.str();
}

// The same text from a byte per module: Koch's word derived by hand, then written.
void BM_KochWordTextHandWritten(benchmark::State& state) {
  if (!koch().program) return state.SkipWithError(koch().error.c_str());
  const int n = static_cast<int>(state.range(0));
  const std::vector<char> word = kochByHand(n);
  CountingBuffer counter;
  std::ostream out(&counter);
  for (auto _ : state) {
    counter.bytes = 0;
    writeByHand(word, out);
  }
  if (!sameTextAsTheEngine(word, n)) return state.SkipWithError("not the engine's text");
  report(state, word.size(), counter.bytes);
}
BENCHMARK(BM_KochWordTextHandWritten)->Arg(8)->Unit(benchmark::kMillisecond);

// `ontogen word --at n` in the process: a fresh world grown from the axiom, its word
// written as text.
void BM_KochDeriveAndWriteText(benchmark::State& state) {
  if (!koch().program) return state.SkipWithError(koch().error.c_str());
  const int n = static_cast<int>(state.range(0));
  CountingBuffer counter;
  std::ostream out(&counter);
  size_t modules = 0;
  for (auto _ : state) {
    counter.bytes = 0;
    World world(koch().program, kBenchWorld);
    world.advanceTo(n, 1.0);
    BufferedOutput buffered(out);
    writeWordText(world, buffered, 6);
    buffered.flush();
    modules = world.rootPool().size();
  }
  if (counter.bytes != 2 * modules - 1) return state.SkipWithError("wrong output size");
  report(state, modules, counter.bytes);
}
BENCHMARK(BM_KochDeriveAndWriteText)->Arg(8)->Unit(benchmark::kMillisecond);

// The same by hand: the word derived as bytes, then written.
void BM_KochDeriveAndWriteTextHandWritten(benchmark::State& state) {
  if (!koch().program) return state.SkipWithError(koch().error.c_str());
  const int n = static_cast<int>(state.range(0));
  CountingBuffer counter;
  std::ostream out(&counter);
  size_t modules = 0;
  for (auto _ : state) {
    counter.bytes = 0;
    const std::vector<char> word = kochByHand(n);
    writeByHand(word, out);
    modules = word.size();
  }
  if (!sameTextAsTheEngine(kochByHand(n), n)) return state.SkipWithError("not the engine's text");
  report(state, modules, counter.bytes);
}
BENCHMARK(BM_KochDeriveAndWriteTextHandWritten)->Arg(8)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace ontogen::bench
