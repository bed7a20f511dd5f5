#pragma once
// Helpers shared by the benchmarks: compiling a program text or a model of models/, and
// finding a module's master. Failures come back as messages for state.SkipWithError, so
// a benchmark whose program does not compile reports an error instead of a time.

#include <sys/resource.h>

#include <benchmark/benchmark.h>

#include <algorithm>
#include <fstream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "core/world.h"
#include "interpreters/set_registry.h"
#include "lang/compiler.h"
#include "model/program.h"

namespace ontogen::bench {

/// Every benchmark world: seed 1, default limits.
inline const WorldDef kBenchWorld{.seed = 1};

/// A compiled program, or the diagnostics that stopped it.
struct Compiled {
  std::shared_ptr<const Program> program;  ///< null on error
  std::string error;                       ///< the formatted diagnostics when program is null
};

/// Compiles a program text the way `ontogen run` does (interpretation blocks checked),
/// with the defines as `--define NAME=VALUE` gives them.
inline Compiled compileText(const std::string& name, std::string text,
                            const std::vector<std::pair<std::string, double>>& defines = {}) {
  DiagnosticSink sink;
  CompileOptions options;
  options.commandSets = commandSets();
  for (const auto& [define, value] : defines) options.defines.push_back({define, value});
  std::shared_ptr<const Program> program = compileSource(name, std::move(text), sink, options);
  if (!program) return {nullptr, name + " does not compile:\n" + formatDiagnostics(sink)};
  return {std::move(program), {}};
}

/// Compiles models/<name> from the source tree.
inline Compiled compileModel(const std::string& name,
                             const std::vector<std::pair<std::string, double>>& defines = {}) {
  const std::string path = std::string(ONTOGEN_SOURCE_DIR) + "/models/" + name;
  std::ifstream in(path, std::ios::binary);
  if (!in) return {nullptr, "cannot read " + path};
  std::ostringstream text;
  text << in.rdbuf();
  return compileText("models/" + name, text.str(), defines);
}

/// Processor time of the whole process so far, user and system (where the kernel zeroes
/// fresh pages), in seconds: on a machine shared with other work, wall time mostly
/// measures the others.
inline double processSeconds() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  auto seconds = [](const timeval& t) { return static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_usec); };
  return seconds(usage.ru_utime) + seconds(usage.ru_stime);
}

/// What cold memory costs: the processor time of the process's first world against the
/// fastest later one of the same benchmark, reported as `first/warm` by the benchmark
/// that runs first in the process (run one alone with --benchmark_filter). Its first
/// world finds no memory to reuse (pools/large_block_cache.h); later ones do.
class FirstAndWarm {
 public:
  FirstAndWarm() : cold_(takeProcessFirst()) {}
  void add(double seconds) {
    if (first_ == 0)
      first_ = seconds;
    else
      warm_ = warm_ == 0 ? seconds : std::min(warm_, seconds);
  }
  void report(benchmark::State& state) const {
    if (!cold_ || warm_ <= 0) return;
    state.counters["first/warm"] = first_ / warm_;
    // What the first world paid more, to set beside the price of the same fresh pages
    // (BM_KochHandWrittenFreshPages less BM_KochHandWritten).
    state.counters["first-warm_ms"] = 1e3 * (first_ - warm_);
  }

 private:
  static bool takeProcessFirst() {
    static bool first = true;
    return std::exchange(first, false);
  }
  bool cold_;
  double first_ = 0, warm_ = 0;
};

/// The master of a module of the root system, by label.
inline std::optional<uint32_t> masterOf(const Program& program, std::string_view label) {
  int index = program.findMaster(label, program.root);
  if (index < 0) return std::nullopt;
  return static_cast<uint32_t>(index);
}

}  // namespace ontogen::bench
