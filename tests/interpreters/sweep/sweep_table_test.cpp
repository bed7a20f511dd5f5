// The table of a sweep: its CSV and JSON by value, the journal's lines read back, and a
// journal whose last line was cut short by a kill.

#include "interpreters/sweep/sweep_table.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

namespace ontogen {
namespace {

SweepTable sample() {
  SweepTable table;
  table.columns = {"N", "seed", "h"};
  table.rows.push_back({0, {"3", "1", "0.30000000000000004"}, ""});
  table.rows.push_back({1, {"4", "1", ""}, "tree.cell:3:7: a \"quoted\", comma"});
  return table;
}

TEST(SweepTable, ValuesAreTheShortestTextThatReadsBack) {
  EXPECT_EQ(formatValue(3), "3");
  EXPECT_EQ(formatValue(-0.0), "0");
  EXPECT_EQ(formatValue(0.1 + 0.2), "0.30000000000000004");
  EXPECT_EQ(formatValue(1e6), "1000000");
  EXPECT_EQ(formatValue(1e300), "1e+300");
  EXPECT_EQ(formatValue(std::nan("")), "");
  EXPECT_EQ(formatValue(std::numeric_limits<double>::infinity()), "");
  for (double value : {0.1, 1.0 / 3, 2.5e-12, -7.25})
    EXPECT_EQ(std::stod(formatValue(value)), value) << value;
}

TEST(SweepTable, CsvAndJsonHoldTheSameRows) {
  std::ostringstream csv, json;
  writeTableCsv(sample(), csv);
  EXPECT_EQ(csv.str(),
            "variant,N,seed,h,error\n"
            "0,3,1,0.30000000000000004,\n"
            "1,4,1,,\"tree.cell:3:7: a \"\"quoted\"\", comma\"\n");
  writeTableJson(sample(), json);
  const nlohmann::json parsed = nlohmann::json::parse(json.str());
  EXPECT_EQ(parsed["columns"], nlohmann::json({"N", "seed", "h"}));
  ASSERT_EQ(parsed["rows"].size(), 2u);
  EXPECT_EQ(parsed["rows"][0]["variant"], 0);
  EXPECT_EQ(parsed["rows"][0]["h"].get<double>(), 0.1 + 0.2);
  EXPECT_TRUE(parsed["rows"][0]["error"].is_null());
  EXPECT_TRUE(parsed["rows"][1]["h"].is_null());
  EXPECT_EQ(parsed["rows"][1]["error"], "tree.cell:3:7: a \"quoted\", comma");
  // The digits as the CSV has them, not printed again.
  EXPECT_NE(json.str().find("\"h\": 0.30000000000000004"), std::string::npos) << json.str();
}

TEST(SweepTable, TheJournalReadsBackAndDropsALineCutShort) {
  const std::filesystem::path path = std::filesystem::temp_directory_path() / "ontogen_sweep_table_test.jsonl";
  const SweepTable table = sample();
  {
    std::ofstream out(path, std::ios::binary);
    out << "{\"sweep\": 1}\n" << journalLine(table.rows[1]) << "\n" << journalLine(table.rows[0]) << "\n";
    out << journalLine(table.rows[0]) << "\n";  // a row written twice counts once
    out << journalLine(table.rows[1]).substr(0, 20);  // killed while writing
  }
  const JournalContents contents = readJournal(path, 3);
  EXPECT_TRUE(contents.exists);
  EXPECT_EQ(contents.header, "{\"sweep\": 1}");
  ASSERT_EQ(contents.rows.size(), 2u);
  EXPECT_EQ(contents.rows[0], table.rows[1]);
  EXPECT_EQ(contents.rows[1], table.rows[0]);
  EXPECT_EQ(contents.goodBytes, std::filesystem::file_size(path) - 20);
  // Lines of another shape are no rows.
  EXPECT_FALSE(parseJournalLine(journalLine(table.rows[0]), 2));
  EXPECT_FALSE(parseJournalLine("{\"variant\": 1, \"values\": [\"x\", \"1\", \"2\"], \"error\": \"\"}", 3));
  EXPECT_FALSE(readJournal(path.string() + ".missing", 3).exists);
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace ontogen
