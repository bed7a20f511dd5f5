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
  const std::string header = "{\"sweep\": 1}";
  {
    std::ofstream out(path, std::ios::binary);
    out << header << "\n" << journalLine(table.rows[1], header) << "\n" << journalLine(table.rows[0], header) << "\n";
    out << journalLine(table.rows[0], header) << "\n";  // a row written twice counts once
    out << journalLine(table.rows[1], header).substr(0, 20);  // killed while writing
  }
  const JournalContents contents = readJournal(path, 3, header);
  EXPECT_TRUE(contents.exists);
  EXPECT_EQ(contents.header, header);
  ASSERT_EQ(contents.rows.size(), 2u);
  EXPECT_EQ(contents.rows[0], table.rows[1]);
  EXPECT_EQ(contents.rows[1], table.rows[0]);
  EXPECT_EQ(contents.rejected, 0u);
  // Lines of another shape are no rows.
  EXPECT_FALSE(parseJournalLine(journalLine(table.rows[0], header), 2, header));
  EXPECT_FALSE(readJournal(path.string() + ".missing", 3, header).exists);
  std::filesystem::remove(path);
}

TEST(SweepTable, AJournalRowChangedOrWrittenUnderAnotherHeaderIsNoRow) {
  const SweepTable table = sample();
  const std::string header = "{\"sweep\": 1}";
  const std::string line = journalLine(table.rows[0], header);
  ASSERT_TRUE(parseJournalLine(line, 3, header));
  EXPECT_EQ(*parseJournalLine(line, 3, header), table.rows[0]);
  // Under other settings (other measures) the same line does not check.
  EXPECT_FALSE(parseJournalLine(line, 3, "{\"sweep\": 2}"));
  // A value changed by hand, or a row without its check, is no row either.
  std::string changed = line;
  const size_t at = changed.find("\"values\":[\"");
  ASSERT_NE(at, std::string::npos) << line;
  changed[at + 11] = changed[at + 11] == '9' ? '8' : '9';
  EXPECT_FALSE(parseJournalLine(changed, 3, header)) << changed;
  EXPECT_FALSE(parseJournalLine("{\"variant\": 1, \"values\": [\"1\", \"1\", \"2\"], \"error\": \"\"}", 3, header));
  // A whole line that does not check is skipped, not the end of the journal.
  const std::filesystem::path path = std::filesystem::temp_directory_path() / "ontogen_sweep_table_check.jsonl";
  {
    std::ofstream out(path, std::ios::binary);
    out << header << "\n" << changed << "\n" << journalLine(table.rows[1], header) << "\n";
  }
  const JournalContents contents = readJournal(path, 3, header);
  ASSERT_EQ(contents.rows.size(), 1u);
  EXPECT_EQ(contents.rows[0], table.rows[1]);
  EXPECT_EQ(contents.rejected, 1u);
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace ontogen
