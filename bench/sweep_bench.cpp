// The variants of a sweep, one after another on one thread: models/stochastic_tree.cell
// over 64 settings and seeds, each compiled with its values, grown, pictured (32 x 32) and
// measured. BM_VariantsThroughRunVariant goes through the library's runVariant (what a
// sweep's worker does, without the journal and the files of its program); the
// hand-written baseline is a plain loop of Runs with the defines given as compile
// options. bench/sweep_bench.sh times `ontogen sweep` itself on 1 and 2 workers and 2
// MPI ranks beside them.

#include <benchmark/benchmark.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "bench/bench_support.h"
#include "interpreters/run.h"
#include "interpreters/sweep/variant_run.h"
#include "lang/variation.h"

namespace ontogen::bench {
namespace {

namespace fs = std::filesystem;

constexpr int kVariants = 64;  // LEN 2 x SHRINK 4 x BRANCH 2 x seeds 4, as bench/sweep_bench.sh

struct Setting {
  double len, shrink, branch;
  uint64_t seed;
};

Setting settingOf(int i) {
  static constexpr double kShrink[] = {0.6, 0.7, 0.8, 0.9};
  return {1.0 + (i / 32) % 2, kShrink[(i / 8) % 4], (i / 4) % 2 ? 0.7 : 0.3, static_cast<uint64_t>(1 + i % 4)};
}

std::string treeText() {
  std::ifstream in(std::string(ONTOGEN_SOURCE_DIR) + "/models/stochastic_tree.cell", std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

RunDef thumbnailRun(const fs::path& out, int i) {
  RunDef def;
  def.stem = "v" + std::to_string(i);
  def.out = out;
  def.world.threads = 1;
  def.world.seed = settingOf(i).seed;
  def.setOptions.formats = "png";
  def.setOptions.render.width = def.setOptions.render.height = 32;
  return def;
}

void BM_VariantsHandWritten(benchmark::State& state) {
  const std::string text = treeText();
  const fs::path out = fs::temp_directory_path() / "ontogen_sweep_bench_hand";
  double endTimes = 0;  // read, so that nothing is optimised away
  for (auto _ : state) {
    for (int i = 0; i < kVariants; ++i) {
      const Setting s = settingOf(i);
      DiagnosticSink sink;
      CompileOptions options;
      options.commandSets = commandSets();
      options.defines = {{"LEN", s.len}, {"SHRINK", s.shrink}, {"BRANCH", s.branch}};
      RunDef def = thumbnailRun(out, i);
      def.program = compileSource("stochastic_tree.cell", text, sink, options);
      if (!def.program) {
        state.SkipWithError("the tree does not compile");
        return;
      }
      Run run(std::move(def));
      if (!run.execute().ok()) {
        state.SkipWithError("a variant failed");
        return;
      }
      endTimes += run.world()->time();
    }
  }
  benchmark::DoNotOptimize(endTimes);
  state.counters["variants/s"] = benchmark::Counter(static_cast<double>(state.iterations()) * kVariants,
                                                    benchmark::Counter::kIsRate);
  fs::remove_all(out);
}
BENCHMARK(BM_VariantsHandWritten)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_VariantsThroughRunVariant(benchmark::State& state) {
  const VariationSpace space(treeText());
  const fs::path out = fs::temp_directory_path() / "ontogen_sweep_bench_library";
  const std::vector<Measure> measures{parseMeasure("h=height")};
  for (auto _ : state) {
    for (int i = 0; i < kVariants; ++i) {
      const Setting s = settingOf(i);
      Genome genome = space.original();
      for (size_t g = 0; g < space.genes().size(); ++g) {
        const std::string& name = space.genes()[g].name;
        genome.values[g] = name == "LEN" ? s.len : name == "SHRINK" ? s.shrink : s.branch;
      }
      VariantDef def;
      def.name = "stochastic_tree.cell";
      def.text = space.programText(genome);
      def.compile.commandSets = commandSets();
      def.run = thumbnailRun(out, i);
      def.measures = measures;
      const VariantResult result = runVariant(std::move(def));
      if (!result.error.empty()) {
        state.SkipWithError(result.error.c_str());
        return;
      }
    }
  }
  state.counters["variants/s"] = benchmark::Counter(static_cast<double>(state.iterations()) * kVariants,
                                                    benchmark::Counter::kIsRate);
  fs::remove_all(out);
}
BENCHMARK(BM_VariantsThroughRunVariant)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace ontogen::bench
