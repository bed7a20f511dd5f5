// The sweep as a library call (batch/sweep.h): the product of defines and seeds, each
// row measured; what a host program (the Python module) gets back.

#include <array>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "batch/sweep.h"
#include "interpreters/formats/png_reader.h"
#include "interpreters/set_registry.h"
#include "lang/compiler.h"
#include "tests/batch/batch_test_support.h"

namespace ontogen::test {
namespace {

namespace fs = std::filesystem;

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
  EXPECT_TRUE(readWholeFile(dir / "out" / "results.csv").starts_with("variant,LEN,S,seed,h,n,error\n"));
}

// A journal row whose checksum holds but whose values are another variant's (written by
// a tool, or a fault that kept the line whole) is run again, not trusted.
TEST(Sweep, AJournalRowThatContradictsItsVariantRunsAgain) {
  const fs::path dir = scratch("contradiction");
  const SweepResult first = runSweep(chainSweep(dir));
  ASSERT_EQ(first.batch.status, BatchStatus::Done) << first.batch.message;
  const std::string journal = readWholeFile(dir / "out" / "journal.jsonl");
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

// The drawn box (x0, y0, x1, y1, inclusive) of the pixels in box {x, y, w, h} of image
// that differ from `ground` by more than 24 levels in some channel; all -1 when none.
std::array<int, 4> drawnBox(const Image& image, const nlohmann::json& box, const uint8_t ground[3]) {
  std::array<int, 4> drawn{-1, -1, -1, -1};
  const int x0 = box[0], y0 = box[1], w = box[2], h = box[3];
  for (int y = y0; y < y0 + h; ++y)
    for (int x = x0; x < x0 + w; ++x) {
      const uint8_t* p = image.rgb.data() + (static_cast<size_t>(y) * image.width + x) * 3;
      bool differs = false;
      for (int c = 0; c < 3; ++c) differs = differs || std::abs(p[c] - ground[c]) > 24;
      if (!differs) continue;
      if (drawn[0] < 0) drawn = {x, y, x, y};
      drawn = {std::min(drawn[0], x), std::min(drawn[1], y), std::max(drawn[2], x), std::max(drawn[3], y)};
    }
  return drawn;
}

// The gallery draws every thumbnail at one scale: the chain with LEN 2 is twice as tall
// as with LEN 1, and so is its drawing on the sheet (each thumbnail alone is framed to
// fill its picture, so there both are as tall). Each tile is labelled with its values,
// in gallery.json and as text drawn under it.
TEST(Sweep, TheGalleryDrawsEveryVariantAtOneScaleAndLabelsIt) {
  const fs::path dir = scratch("gallery");
  SweepDef def = chainSweep(dir);
  def.defines = {{"LEN", {1, 2}, {}}, {"S", {0.5}, {}}};
  def.seeds = {7, 7};
  def.settings.width = def.settings.height = 96;
  const SweepResult result = runSweep(def);
  ASSERT_EQ(result.batch.status, BatchStatus::Done) << result.batch.message;
  const nlohmann::json gallery = nlohmann::json::parse(readWholeFile(dir / "out" / "gallery.json"));
  const std::optional<Image> sheet = readPng(dir / "out" / "gallery.png");
  ASSERT_TRUE(sheet);
  ASSERT_EQ(gallery["tiles"].size(), 2u) << gallery.dump();
  EXPECT_EQ(gallery["tiles"][0]["label"], "LEN=1 S=0.5");
  EXPECT_EQ(gallery["tiles"][1]["label"], "LEN=2 S=0.5");
  EXPECT_EQ(sheet->width, gallery["width"].get<int>());
  EXPECT_EQ(sheet->height, gallery["height"].get<int>());
  // The thumbnails alone: both chains as tall, each framed to fill its picture.
  const std::optional<Image> small = readPng(dir / "out" / "thumbnails" / "v0000.png");
  const std::optional<Image> large = readPng(dir / "out" / "thumbnails" / "v0001.png");
  ASSERT_TRUE(small && large);
  const nlohmann::json whole = {0, 0, 96, 96};
  const auto smallAlone = drawnBox(*small, whole, kBackground), largeAlone = drawnBox(*large, whole, kBackground);
  EXPECT_NEAR(smallAlone[3] - smallAlone[1], largeAlone[3] - largeAlone[1], 2);
  // On the sheet: the LEN 2 chain twice as tall as the LEN 1 chain, the larger as tall
  // as its thumbnail.
  const auto a = drawnBox(*sheet, gallery["tiles"][0]["box"], kBackground);
  const auto b = drawnBox(*sheet, gallery["tiles"][1]["box"], kBackground);
  ASSERT_GE(a[0], 0);
  ASSERT_GE(b[0], 0);
  const double heightA = a[3] - a[1] + 1, heightB = b[3] - b[1] + 1;
  EXPECT_NEAR(heightB / heightA, 2.0, 0.1) << heightA << " and " << heightB << " pixels";
  EXPECT_NEAR(heightB, largeAlone[3] - largeAlone[1] + 1, 1);
  EXPECT_DOUBLE_EQ(gallery["tiles"][1]["scale"].get<double>(), 1.0);
  EXPECT_NEAR(gallery["tiles"][0]["scale"].get<double>(), 0.5, 0.02);
  // The labels are drawn: dark text in each tile's label band, the longer label wider.
  const uint8_t sheetGround[3] = {210, 210, 206};
  const auto labelA = drawnBox(*sheet, gallery["tiles"][0]["label_box"], sheetGround);
  const auto labelB = drawnBox(*sheet, gallery["tiles"][1]["label_box"], sheetGround);
  ASSERT_GE(labelA[0], 0) << "no label drawn";
  ASSERT_GE(labelB[0], 0) << "no label drawn";
  // "LEN=1 S=0.5" fits one line of 96 pixels (16 characters of 6): 11 characters wide.
  EXPECT_EQ(labelA[2] - labelA[0] + 1, 10 * 6 + 5);
  EXPECT_EQ(labelA[3] - labelA[1] + 1, 7);
}

}  // namespace
}  // namespace ontogen::test
