// A sweep's journal is not trusted: a row changed since it was written, a row whose
// values are not its variant's, or rows measured by other measures run again; an empty
// journal or one whose first line was cut short is written anew; the journal follows the
// rule of every output (a link written through, no FIFO or device read or replaced).

#include <sys/stat.h>

#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/apps/cli_support.h"

namespace ontogen::test {
namespace {

// A chain of 3 segments, LEN (1 + 0.5 + 0.25) tall, whatever the seed.
const std::string kChain =
    "lsystem chain {\n"
    "  #define LEN 1\n"
    "  #until 3\n"
    "  axiom A(1)\n"
    "  A(s) -> F(LEN * s) A(s * 0.5)\n"
    "}\n";
const std::string kFlags = " --define LEN=1,2 --seeds 1:2 --size 16x16 --workers 1 --no-progress";

std::vector<std::string> linesOf(const std::string& text) {
  std::vector<std::string> result;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) result.push_back(line);
  return result;
}

std::string joinLines(const std::vector<std::string>& lines) {
  std::string text;
  for (const std::string& line : lines) text += line + "\n";
  return text;
}

struct Swept {
  fs::path dir, program;
  std::string table;  // results.csv of the whole sweep
};

Swept sweepOnce(const std::string& name, const std::string& measures = " --measure h=height") {
  Swept swept;
  swept.dir = scratchDir(name);
  swept.program = writeFile(swept.dir / "chain.cell", kChain);
  CliResult whole =
      runOntogen("sweep " + swept.program.string() + kFlags + measures + " --out " + (swept.dir / "out").string());
  EXPECT_EQ(whole.exitCode, 0) << whole.err;
  swept.table = readWholeFile(swept.dir / "out" / "results.csv");
  EXPECT_EQ(swept.table, "variant,LEN,seed,h,error\n0,1,1,1.75,\n1,1,2,1.75,\n2,2,1,3.5,\n3,2,2,3.5,\n");
  return swept;
}

CliResult resume(const Swept& swept, const std::string& measures = " --measure h=height") {
  return runOntogen("sweep " + swept.program.string() + kFlags + measures + " --resume --out " +
                    (swept.dir / "out").string());
}

TEST(SweepJournal, ARowChangedInTheJournalRunsAgain) {
  const Swept swept = sweepOnce("journal_changed_row");
  std::vector<std::string> journal = linesOf(readWholeFile(swept.dir / "out" / "journal.jsonl"));
  ASSERT_EQ(journal.size(), 5u);
  bool changed = false;
  for (std::string& line : journal)
    if (const size_t at = line.find("\"3.5\""); at != std::string::npos && !changed) {
      line.replace(at, 5, "\"99\"");
      changed = true;
    }
  ASSERT_TRUE(changed);
  writeFile(swept.dir / "out" / "journal.jsonl", joinLines(journal));
  const CliResult resumed = resume(swept);
  ASSERT_EQ(resumed.exitCode, 0) << resumed.err;
  EXPECT_EQ(readWholeFile(swept.dir / "out" / "results.csv"), swept.table);
  // The journal holds each row once, as it is now.
  const std::string rewritten = readWholeFile(swept.dir / "out" / "journal.jsonl");
  EXPECT_EQ(linesOf(rewritten).size(), 5u);
  EXPECT_EQ(rewritten.find("\"99\""), std::string::npos) << rewritten;
}

TEST(SweepJournal, RowsThatContradictTheirVariantsRunAgain) {
  const Swept swept = sweepOnce("journal_contradiction");
  // The rows of variants 0 (LEN 1) and 2 (LEN 2) each claim the other's number.
  std::string journal = readWholeFile(swept.dir / "out" / "journal.jsonl");
  for (const auto& [from, to] : {std::pair{"\"variant\":0", "\"variant\":X"}, std::pair{"\"variant\":2", "\"variant\":0"},
                                 std::pair{"\"variant\":X", "\"variant\":2"}}) {
    const size_t at = journal.find(from);
    ASSERT_NE(at, std::string::npos) << journal;
    journal.replace(at, std::string(from).size(), to);
  }
  writeFile(swept.dir / "out" / "journal.jsonl", journal);
  const CliResult resumed = resume(swept);
  ASSERT_EQ(resumed.exitCode, 0) << resumed.err;
  EXPECT_EQ(readWholeFile(swept.dir / "out" / "results.csv"), swept.table);
}

TEST(SweepJournal, RowsOfChangedMeasuresRunAgainMeasuredAnew) {
  const Swept swept = sweepOnce("journal_measures");
  // The same variants measured otherwise: every row runs again, none is kept.
  const CliResult doubled = resume(swept, " --measure h=2*height --measure n=cells");
  ASSERT_EQ(doubled.exitCode, 0) << doubled.err;
  EXPECT_EQ(readWholeFile(swept.dir / "out" / "results.csv"),
            "variant,LEN,seed,h,n,error\n0,1,1,3.5,4,\n1,1,2,3.5,4,\n2,2,1,7,4,\n3,2,2,7,4,\n");
  // Other variants are still another sweep.
  const CliResult other = runOntogen("sweep " + swept.program.string() +
                                     " --define LEN=1,3 --seeds 1:2 --size 16x16 --workers 1 --measure h=height "
                                     "--resume --out " + (swept.dir / "out").string());
  EXPECT_EQ(other.exitCode, 2);
  EXPECT_NE(other.err.find("holds a sweep of other settings"), std::string::npos) << other.err;
}

TEST(SweepJournal, AnEmptyJournalOrOneWithItsFirstLineCutIsWrittenAnew) {
  const Swept swept = sweepOnce("journal_cut_header");
  const std::string header = linesOf(readWholeFile(swept.dir / "out" / "journal.jsonl"))[0];
  for (const std::string& left : {std::string(), header.substr(0, header.size() / 2)}) {
    for (const bool resuming : {false, true}) {
      fs::remove_all(swept.dir / "out");
      fs::create_directories(swept.dir / "out");
      writeFile(swept.dir / "out" / "journal.jsonl", left);
      const CliResult again = runOntogen("sweep " + swept.program.string() + kFlags + " --measure h=height" +
                                         (resuming ? " --resume" : "") + " --out " + (swept.dir / "out").string());
      ASSERT_EQ(again.exitCode, 0) << left.size() << " bytes left, resuming " << resuming << ": " << again.err;
      EXPECT_EQ(readWholeFile(swept.dir / "out" / "results.csv"), swept.table);
      EXPECT_EQ(linesOf(readWholeFile(swept.dir / "out" / "journal.jsonl"))[0], header);
    }
  }
}

TEST(SweepJournal, TheJournalIsWrittenThroughALinkAndNeverIsAFifo) {
  const fs::path dir = scratchDir("journal_kinds");
  const fs::path program = writeFile(dir / "chain.cell", kChain);
  fs::create_directories(dir / "linked");
  fs::create_symlink("../kept.jsonl", dir / "linked" / "journal.jsonl");
  const CliResult linked = runOntogen("sweep " + program.string() + kFlags + " --measure h=height --out " +
                                      (dir / "linked").string());
  ASSERT_EQ(linked.exitCode, 0) << linked.err;
  EXPECT_TRUE(fs::is_symlink(dir / "linked" / "journal.jsonl"));
  EXPECT_EQ(linesOf(readWholeFile(dir / "kept.jsonl")).size(), 5u);

  fs::create_directories(dir / "fifo");
  ASSERT_EQ(mkfifo((dir / "fifo" / "journal.jsonl").c_str(), 0600), 0);
  for (const std::string resuming : {"", " --resume"}) {
    const CliResult fifo = runOntogen("sweep " + program.string() + kFlags + " --measure h=height" + resuming +
                                          " --out " + (dir / "fifo").string(),
                                      30);
    EXPECT_EQ(fifo.exitCode, 4) << fifo.err;
    EXPECT_NE(fifo.err.find("journal.jsonl': it is a FIFO"), std::string::npos) << fifo.err;
    EXPECT_EQ(fifo.err.find('\n'), fifo.err.size() - 1) << "one line: " << fifo.err;
  }
  EXPECT_FALSE(fs::is_regular_file(dir / "fifo" / "journal.jsonl"));
}

}  // namespace
}  // namespace ontogen::test
