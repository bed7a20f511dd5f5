// `ontogen word` streams its words cell by cell: the same text and JSON as the records
// of captureWord, nothing on standard output when a later time fails, and far less
// memory than a record per module.

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <functional>
#include <string>

#include "tests/apps/cli_support.h"

namespace ontogen::test {
namespace {

size_t countOf(const std::string& text, const std::string& what) {
  size_t count = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++count;
  return count;
}

TEST(WordStream, KochTextAtSeveralTimes) {
  const CliResult result = runOntogen("word " + modelPath("koch.cell") + " --at 1,4");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  const size_t newline = result.out.find('\n');
  ASSERT_NE(newline, std::string::npos);
  EXPECT_EQ(result.out.substr(0, newline), "t = 1: F + F - F - F + F");
  const std::string second = result.out.substr(newline + 1);
  ASSERT_EQ(second.rfind("t = 4: F + F - F", 0), 0u) << second.substr(0, 40);
  EXPECT_EQ(countOf(second, "F"), 625u);  // 5^4
  EXPECT_EQ(countOf(second, " "), 1248u + 3u);  // between 1249 modules, and three in "t = 4: "
  EXPECT_EQ(second.back(), '\n');
}

TEST(WordStream, NestedPoolsInJsonAndText) {
  const CliResult json = runOntogen("word " + modelPath("orchard.cell") + " --at 0,2 --json");
  ASSERT_EQ(json.exitCode, 0) << json.err;
  const auto document = nlohmann::json::parse(json.out);
  ASSERT_EQ(document["times"].size(), 2u);
  const auto& cells = document["times"][1]["cells"];
  ASSERT_EQ(cells.size(), 5u);
  EXPECT_EQ(cells[0]["label"], "tree");
  ASSERT_EQ(cells[0]["pool"].size(), 2u);
  EXPECT_EQ(cells[0]["pool"][0]["label"], "Trunk");
  EXPECT_EQ(cells[0]["pool"][0]["parent"], cells[0]["id"]);
  EXPECT_EQ(cells[1]["label"], "Gap");
  EXPECT_FALSE(cells[1].contains("pool"));
  // The layout too: two spaces a level, a list's bracket under what holds it.
  EXPECT_NE(json.out.find("{\"times\": [\n  {\"t\": 0, \"cells\": [\n    {\"label\": \"tree\""), std::string::npos)
      << json.out.substr(0, 200);
  EXPECT_NE(json.out.find(", \"pool\": [\n      {\"label\": \"Trunk\""), std::string::npos);
  EXPECT_EQ(json.out.substr(json.out.size() - 15), "    ]}\n  ]}\n]}\n");

  const CliResult text = runOntogen("word " + modelPath("orchard.cell") + " --at 2 --precision 3");
  ASSERT_EQ(text.exitCode, 0) << text.err;
  EXPECT_EQ(text.out, "t = 2: tree(5) { Trunk(0.998) Bud(0) } Gap tree(7) { Trunk(1.4) Bud(0) } Gap tree(4) { Trunk(0.798) Bud(0) }\n");
}

// The compact JSON is the full one less ids, parents and defaults: a cell of a label
// alone is its label, any other an object of the fields that differ from their defaults.
TEST(WordStream, CompactJsonIsTheFullOneLessItsDefaults) {
  const CliResult koch = runOntogen("word " + modelPath("koch.cell") + " --at 0,1 --json=compact");
  ASSERT_EQ(koch.exitCode, 0) << koch.err;
  EXPECT_EQ(koch.out,
            "{\"form\": \"compact\", \"times\": [\n  {\"t\": 0, \"cells\": [\"F\"]},\n"
            "  {\"t\": 1, \"cells\": [\"F\",\"+\",\"F\",\"-\",\"F\",\"-\",\"F\",\"+\",\"F\"]}\n]}\n");

  const std::string orchard = "word " + modelPath("orchard.cell") + " --at 0,2";
  const CliResult full = runOntogen(orchard + " --json");
  const CliResult compact = runOntogen(orchard + " --json=compact");
  ASSERT_EQ(full.exitCode, 0) << full.err;
  ASSERT_EQ(compact.exitCode, 0) << compact.err;
  // Each full cell less its ids, parents and defaults is the compact one.
  std::function<nlohmann::json(const nlohmann::json&)> lessDefaults = [&](const nlohmann::json& cell) {
    nlohmann::json kept = {{"label", cell["label"]}};
    if (!cell["params"].empty()) kept["params"] = cell["params"];
    if (cell["developed"] != cell["params"]) kept["developed"] = cell["developed"];
    if (cell.contains("position")) kept["position"] = cell["position"];
    if (cell.contains("pool")) {
      kept["pool"] = nlohmann::json::array();
      for (const auto& inner : cell["pool"]) kept["pool"].push_back(lessDefaults(inner));
    }
    return kept.size() == 1 ? kept["label"] : kept;
  };
  nlohmann::json expected = {{"form", "compact"}, {"times", nlohmann::json::array()}};
  const nlohmann::json fullDocument = nlohmann::json::parse(full.out);
  for (const auto& time : fullDocument["times"]) {
    nlohmann::json cells = nlohmann::json::array();
    for (const auto& cell : time["cells"]) cells.push_back(lessDefaults(cell));
    expected["times"].push_back(nlohmann::json::object({{"t", time["t"]}, {"cells", cells}}));
  }
  EXPECT_EQ(nlohmann::json::parse(compact.out), expected) << compact.out;
  EXPECT_NE(compact.out.find("{\"label\": \"tree\", \"params\": [5], \"pool\": [{\"label\": \"Trunk\""), std::string::npos)
      << compact.out;

  const CliResult wrong = runOntogen("word " + modelPath("koch.cell") + " --at 1 --json=short");
  EXPECT_EQ(wrong.exitCode, 2);
  EXPECT_EQ(wrong.out, "");
  EXPECT_NE(wrong.err.find("--json: short not in {full,compact}"), std::string::npos) << wrong.err;
}

TEST(WordStream, NothingPrintedWhenALaterTimeFails) {
  for (const char* format : {"", " --json", " --json=compact"}) {
    const CliResult result = runOntogen("word " + modelPath("koch.cell") + " --at 1,3 --max-cells 20" + format);
    EXPECT_EQ(result.exitCode, 3) << format;
    EXPECT_EQ(result.out, "") << format;
    EXPECT_NE(result.err.find("the cell limit"), std::string::npos) << result.err;
  }
}

// Koch at n = 8 grows without its ids under 19 MiB, and JSON prints ids: giving the word
// its ids again would pass the limit, which is said before anything is printed, the
// earlier time's word included. The text reads no ids and is printed under the same limit.
TEST(WordStream, NothingPrintedWhenGivingTheWordItsIdsPassesTheMemoryLimit) {
  const std::string command = "word " + modelPath("koch.cell") + " --at 1,8";
  const CliResult json = runOntogen(command + " --json --max-memory 19");
  EXPECT_EQ(json.exitCode, 3);
  EXPECT_EQ(json.out, "");
  EXPECT_NE(json.err.find("its ids again"), std::string::npos) << json.err;
  EXPECT_NE(json.err.find("--max-memory"), std::string::npos) << json.err;
  const CliResult text = runOntogen(command + " --max-memory 19");
  ASSERT_EQ(text.exitCode, 0) << text.err;
  EXPECT_EQ(countOf(text.out, "F"), 5u + 390'625u);  // 5 at t = 1, 5^8 at t = 8
  // The compact JSON prints no ids either.
  const CliResult compact = runOntogen(command + " --json=compact --max-memory 19");
  ASSERT_EQ(compact.exitCode, 0) << compact.err;
  const auto document = nlohmann::json::parse(compact.out);
  ASSERT_EQ(document["times"].size(), 2u);
  EXPECT_EQ(document["times"][1]["cells"].size(), 2 * 390'625u - 1);
  EXPECT_EQ(countOf(compact.out, "\"F\""), 5u + 390'625u);
  const CliResult roomier = runOntogen(command + " --json --max-memory 24");
  ASSERT_EQ(roomier.exitCode, 0) << roomier.err;
  EXPECT_EQ(countOf(roomier.out, "\"label\": \"F\""), 5u + 390'625u);
}

}  // namespace
}  // namespace ontogen::test
