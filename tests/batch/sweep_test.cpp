// The sweep as a library call (batch/sweep.h): the product of defines and seeds, each
// row measured; what a host program (the Python module) gets back.

#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "batch/sweep.h"
#include "interpreters/set_registry.h"
#include "lang/compiler.h"

namespace ontogen::test {
namespace {

namespace fs = std::filesystem;

// A chain of 3 segments, LEN (1 + S + S^2) tall; A counts the apices (always 1).
const std::string kChain =
    "lsystem chain {\n"
    "  #define LEN 1\n"
    "  #define S 0.5\n"
    "  #until 3\n"
    "  axiom A(1)\n"
    "  A(s) -> F(LEN * s) A(s * S)\n"
    "}\n";

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::path(ONTOGEN_BINARY_DIR) / "batch_test" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string readAll(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

SweepDef chainSweep(const fs::path& dir) {
  SweepDef def;
  def.settings.path = (dir / "chain.cell").string();
  def.settings.stem = "chain";
  def.settings.text = kChain;
  DiagnosticSink sink;
  CompileOptions options;
  options.commandSets = commandSets();
  def.settings.program = compileSource(def.settings.path, kChain, sink, options);
  def.settings.measures = {"h=height", "n=count(A)"};
  def.settings.width = def.settings.height = 16;
  def.settings.workers = 2;
  def.defines = {{"LEN", {1, 2}, {}}, {"S", {0.5, 0.25}, {}}};
  def.seeds = {7, 8};
  def.out = dir / "out";
  return def;
}

TEST(Sweep, RowsAreTheProductOfDefinesAndSeedsMeasured) {
  const fs::path dir = scratch("product");
  SweepDef def = chainSweep(dir);
  ASSERT_TRUE(def.settings.program);
  const SweepResult result = runSweep(def);
  ASSERT_EQ(result.batch.status, BatchStatus::Done) << result.batch.message;
  EXPECT_EQ(result.count, 8u);
  EXPECT_EQ(result.batch.failed, 0u);
  const std::vector<std::string> columns{"LEN", "S", "seed", "h", "n"};
  EXPECT_EQ(result.batch.table.columns, columns);
  ASSERT_EQ(result.batch.table.rows.size(), 8u);
  for (uint64_t i = 0; i < 8; ++i) {
    const SweepRow& row = result.batch.table.rows[i];
    EXPECT_EQ(row.variant, i);
    // The first define outermost, the seed innermost.
    const double len = i < 4 ? 1 : 2, s = (i / 2) % 2 == 0 ? 0.5 : 0.25;
    ASSERT_EQ(row.values.size(), 5u);
    EXPECT_EQ(row.values[0], formatValue(len));
    EXPECT_EQ(row.values[1], formatValue(s));
    EXPECT_EQ(row.values[2], std::to_string(7 + i % 2));
    EXPECT_DOUBLE_EQ(std::stod(row.values[3]), len * (1 + s + s * s)) << "variant " << i;
    EXPECT_EQ(row.values[4], "1");
    EXPECT_TRUE(row.error.empty()) << row.error;
  }
  EXPECT_TRUE(readAll(dir / "out" / "results.csv").starts_with("variant,LEN,S,seed,h,n,error\n"));
}

// A journal row whose checksum holds but whose values are another variant's (written by
// a tool, or a fault that kept the line whole) is run again, not trusted.
TEST(Sweep, AJournalRowThatContradictsItsVariantRunsAgain) {
  const fs::path dir = scratch("contradiction");
  const SweepResult first = runSweep(chainSweep(dir));
  ASSERT_EQ(first.batch.status, BatchStatus::Done) << first.batch.message;
  const std::string journal = readAll(dir / "out" / "journal.jsonl");
  const std::string header = journal.substr(0, journal.find('\n'));
  SweepRow forged = first.batch.table.rows[5];  // LEN 2, S 0.5, seed 8 ...
  forged.variant = 0;                           // ... claiming to be LEN 1, S 0.5, seed 7
  std::string kept;
  {
    std::istringstream in(journal);
    for (std::string line; std::getline(in, line);)
      if (line.find("\"variant\":0}") == std::string::npos) kept += line + "\n";
  }
  std::ofstream(dir / "out" / "journal.jsonl", std::ios::binary) << kept << journalLine(forged, header) << "\n";
  SweepDef again = chainSweep(dir);
  again.resume = true;
  const SweepResult resumed = runSweep(again);
  ASSERT_EQ(resumed.batch.status, BatchStatus::Done) << resumed.batch.message;
  EXPECT_EQ(resumed.batch.table.rows, first.batch.table.rows);
}

TEST(Sweep, ADefineTheProgramDoesNotHaveIsRefusedWithItsName) {
  const fs::path dir = scratch("unknown_define");
  SweepDef def = chainSweep(dir);
  def.defines = {{"WIDTH", {1}, {}}};
  const SweepResult result = runSweep(def);
  EXPECT_EQ(result.batch.status, BatchStatus::Refused);
  EXPECT_NE(result.batch.message.find("no #define WIDTH"), std::string::npos) << result.batch.message;
  EXPECT_FALSE(fs::exists(dir / "out"));
}

}  // namespace
}  // namespace ontogen::test
