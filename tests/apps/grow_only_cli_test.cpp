// `ontogen run FILE --format none --stats`: the model grows and nothing is interpreted
// or written, not even the output directory; the statistics are those of a run that
// draws the same model.

#include <gtest/gtest.h>

#include <string>

#include "tests/apps/cli_support.h"

namespace ontogen::test {
namespace {

// The value after `name ` in a --stats line ("cells 31249, ...").
std::string statOf(const std::string& stats, const std::string& name) {
  const size_t at = stats.find(name + " ");
  if (at == std::string::npos) return "";
  const size_t start = at + name.size() + 1;
  return stats.substr(start, stats.find(',', start) - start);
}

TEST(GrowOnly, GrowsKochAndWritesNothing) {
  const fs::path dir = scratchDir("grow_only_koch");
  const fs::path out = dir / "out";
  const CliResult result = runOntogen("run " + modelPath("koch.cell") + " --until 6 --format none --stats --out " + out.string());
  ASSERT_EQ(result.exitCode, 0) << result.err;
  // Generation 6 of F -> F+F-F-F+F: 5^6 F and 5^6 - 1 turns.
  EXPECT_EQ(statOf(result.out, "cells"), "31249") << result.out;
  EXPECT_EQ(statOf(result.out, "time"), "6") << result.out;
  EXPECT_EQ(statOf(result.out, "files"), "0") << result.out;
  EXPECT_NE(statOf(result.out, "held"), "") << result.out;
  EXPECT_FALSE(fs::exists(out)) << "the output directory was made";
  EXPECT_EQ(result.err.find("wrote"), std::string::npos) << result.err;
}

// --stats ends with the rewrites each strategy made (core/rewrite_plan.h): Koch's word
// stays under 2^15 modules to generation 6, so on any thread count each of the six steps
// walks it by its table on one thread.
TEST(GrowOnly, StatisticsSayHowTheWordWasRewritten) {
  for (const char* threads : {"1", "3"}) {
    const CliResult result =
        runOntogen("run " + modelPath("koch.cell") + " --until 6 --format none --stats --threads " + threads);
    ASSERT_EQ(result.exitCode, 0) << result.err;
    EXPECT_NE(result.out.find(" s, rewrites: table-alone 6\n"), std::string::npos)
        << threads << " threads: " << result.out;
  }
}

TEST(GrowOnly, StatisticsMatchARunThatDraws) {
  const fs::path dir = scratchDir("grow_only_same");
  const std::string model = modelPath("anabaena.cell");
  const CliResult grown = runOntogen("run " + model + " --until 12 --format none --stats --seed 5");
  const CliResult drawn =
      runOntogen("run " + model + " --until 12 --format svg --frames 4 --stats --seed 5 --out " + (dir / "out").string());
  ASSERT_EQ(grown.exitCode, 0) << grown.err;
  ASSERT_EQ(drawn.exitCode, 0) << drawn.err;
  for (const char* name : {"time", "cells", "events", "cells born"})
    EXPECT_EQ(statOf(grown.out, name), statOf(drawn.out, name)) << name << "\n" << grown.out << drawn.out;
  EXPECT_NE(statOf(grown.out, "cells"), "1");
  EXPECT_EQ(statOf(drawn.out, "files"), "4");
}

TEST(GrowOnly, TakesNoInterpretationOrOtherFormats) {
  const std::string model = modelPath("koch.cell");
  const CliResult withSet = runOntogen("run " + model + " --format none --interpret music");
  EXPECT_EQ(withSet.exitCode, 2);
  EXPECT_NE(withSet.err.find("--format none grows without interpreting"), std::string::npos) << withSet.err;
  const CliResult mixed = runOntogen("run " + model + " --format glb,none --out " + scratchDir("grow_only_mixed").string());
  EXPECT_EQ(mixed.exitCode, 2);
  EXPECT_NE(mixed.err.find("goes alone"), std::string::npos) << mixed.err;
}

}  // namespace
}  // namespace ontogen::test
