// `ontogen sweep` and `ontogen evolve` end to end: the same table on one worker, on all,
// and on three MPI ranks; a sweep killed midway and resumed gives the identical table; a
// variant past --max-cells is an error row; an evolution is reproducible and, rewarded
// for height, grows taller trees.

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <set>
#include <sstream>
#include <thread>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/apps/cli_support.h"
#include "tests/checkers.h"

namespace ontogen::test {
namespace {

// models/stochastic_tree.cell: with BRANCH = 0 a chain of 5 segments, LEN (1 + S + S^2 +
// S^3 + S^4) tall; with BRANCH = 1 a binary tree of 249 modules. Copied into the test's
// folder, so that the variants' files are named after it there.
fs::path treeFile(const fs::path& dir) {
  return writeFile(dir / "tree.cell", readWholeFile(modelPath("stochastic_tree.cell")));
}

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> result;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) result.push_back(line);
  return result;
}

// The row after its first `fields` fields.
std::string after(const std::string& row, int fields) {
  size_t at = 0;
  for (int i = 0; i < fields; ++i) at = row.find(',', at) + 1;
  return row.substr(at);
}

// Everything a sweep writes but its journal (whose rows are in the order they finished).
std::string outputsOf(const fs::path& dir) {
  std::string all = readWholeFile(dir / "results.csv") + readWholeFile(dir / "results.json") +
                    readWholeFile(dir / "gallery.png") + readWholeFile(dir / "gallery.json");
  for (const char* folder : {"thumbnails", "programs"}) {
    std::vector<fs::path> files;
    for (const auto& entry : fs::directory_iterator(dir / folder)) files.push_back(entry.path());
    std::sort(files.begin(), files.end());
    for (const fs::path& file : files) all += file.filename().string() + readWholeFile(file);
  }
  return all;
}

// Skips (fails in CI) where ontogen has no MPI or mpirun is missing; skips under the
// sanitizers, where Open MPI's own allocations read as leaks (the gcc pass runs mpirun).
#define ONTOGEN_REQUIRE_MPI()                                                                                   \
  do {                                                                                                          \
    if (*ONTOGEN_SANITIZED) GTEST_SKIP() << "mpirun is left to the pass without sanitizers";                  \
    ONTOGEN_REQUIRE_CHECKER(ONTOGEN_TEST_MPI && std::system("command -v mpirun >/dev/null 2>&1") == 0,          \
                            "ontogen is built without MPI or mpirun is missing (openmpi-bin, libopenmpi-dev)"); \
  } while (false)

// `ontogen ARGS` as 3 MPI ranks on this machine; its exit code, its output in `log`.
int runOnThreeRanks(const std::string& args, const fs::path& log) {
  return runOntogenShell(args + " >" + log.string() + " 2>&1",
                         "timeout 120 mpirun --oversubscribe --allow-run-as-root -n 3 ")
      .exitCode;
}

const std::string kSweepFlags =
    " --define LEN=1,2 --define SHRINK=0.5:0.9:2 --define BRANCH=0.3,0.7 --seeds 1:4 --size 48x48"
    " --measure h=height --measure 'apices=count(A)' --measure n=cells";

TEST(SweepCli, TheTableIsTheSameOnOneWorkerAllWorkersAndThreeRanks) {
  const fs::path dir = scratchDir("sweep_workers");
  const fs::path tree = treeFile(dir);
  CliResult one = runOntogen("sweep " + tree.string() + kSweepFlags + " --workers 1 --out " + (dir / "one").string());
  ASSERT_EQ(one.exitCode, 0) << one.err;
  CliResult all = runOntogen("sweep " + tree.string() + kSweepFlags + " --out " + (dir / "all").string());
  ASSERT_EQ(all.exitCode, 0) << all.err;

  const std::vector<std::string> table = lines(readWholeFile(dir / "one" / "results.csv"));
  ASSERT_EQ(table.size(), 1u + 2 * 2 * 2 * 4);
  EXPECT_EQ(table[0], "variant,LEN,SHRINK,BRANCH,seed,h,apices,n,error");
  // The product in a fixed order: the first define outermost, the seed innermost.
  EXPECT_TRUE(table[1].starts_with("0,1,0.5,0.3,1,")) << table[1];
  EXPECT_TRUE(table[2].starts_with("1,1,0.5,0.3,2,")) << table[2];
  EXPECT_TRUE(table[5].starts_with("4,1,0.5,0.7,1,")) << table[5];
  EXPECT_TRUE(table[32].starts_with("31,2,0.9,0.7,4,")) << table[32];
  for (size_t row = 1; row < table.size(); ++row) EXPECT_TRUE(table[row].ends_with(",")) << "no error: " << table[row];
  // Seeds change the stochastic tree: the four seeds of one setting differ somewhere.
  std::set<std::string> ofOneSetting;
  for (int row = 1; row <= 4; ++row) ofOneSetting.insert(after(table[row], 5));
  EXPECT_GT(ofOneSetting.size(), 1u);
  EXPECT_EQ(outputsOf(dir / "one"), outputsOf(dir / "all"));

  // The JSON holds the same rows, the values as numbers.
  const nlohmann::json json = nlohmann::json::parse(readWholeFile(dir / "one" / "results.json"));
  ASSERT_EQ(json["rows"].size(), 32u);
  EXPECT_EQ(json["rows"][31]["LEN"], 2);
  EXPECT_EQ(json["rows"][31]["seed"], 4);
  EXPECT_TRUE(json["rows"][31]["error"].is_null());

  // Any row runs alone from its program, and grows the same tree.
  const fs::path program = dir / "one" / "programs" / "v0005.cell";
  const std::string text = readWholeFile(program);
  EXPECT_NE(text.find("#define BRANCH 0.7\n"), std::string::npos) << text;
  EXPECT_NE(text.find("// ontogen run v0005.cell --seed 2"), std::string::npos) << text;
  CliResult alone = runOntogen("sweep " + program.string() + " --seed 2 --size 48x48 --measure h=height "
                               "--measure 'apices=count(A)' --measure n=cells --out " + (dir / "alone").string());
  ASSERT_EQ(alone.exitCode, 0) << alone.err;
  const std::string row5 = after(table[6], 5);
  const std::vector<std::string> aloneTable = lines(readWholeFile(dir / "alone" / "results.csv"));
  ASSERT_EQ(aloneTable.size(), 2u);
  EXPECT_EQ(aloneTable[1], "0,2," + row5);

  ONTOGEN_REQUIRE_MPI();
  const fs::path ranks = dir / "ranks";
  ASSERT_EQ(runOnThreeRanks("sweep " + tree.string() + kSweepFlags + " --workers 1 --out " + ranks.string(),
                            dir / "mpi_out.txt"),
            0)
      << readWholeFile(dir / "mpi_out.txt");
  EXPECT_EQ(outputsOf(dir / "one"), outputsOf(ranks));
}

// The arguments of `sweep TREE FLAGS --out OUT`, FLAGS split at spaces (they hold no quotes),
// for a sweep started without a shell.
std::vector<std::string> sweepArguments(const fs::path& tree, const std::string& flags, const fs::path& out) {
  std::vector<std::string> args{"sweep", tree.string()};
  std::istringstream words(flags);
  for (std::string word; words >> word;) args.push_back(word);
  args.insert(args.end(), {"--out", out.string()});
  return args;
}

// What a SIGKILL leaves once `rows` variants are journalled: the journal's header and
// those rows and no table (the pictures and programs of later rows may be there already,
// as when the kill comes between writing them and journalling the row). Made by hand
// from a finished sweep when the kill came too late on a busy machine.
void cutAfter(const fs::path& out, size_t rows) {
  const std::vector<std::string> journal = lines(readWholeFile(out / "journal.jsonl"));
  std::string kept;
  for (size_t i = 0; i < 1 + rows && i < journal.size(); ++i) kept += journal[i] + "\n";
  writeFile(out / "journal.jsonl", kept);
  for (const char* file : {"results.csv", "results.json", "gallery.png"}) fs::remove(out / file);
}

// A sweep signalled once it has journalled `rows` rows. The variants take milliseconds, so
// on a busy machine the signal can come after the last row: that is not the case under
// test, and the caller checks what the sweep left either way. Returns the wait status.
int signalledAfterRows(const std::vector<std::string>& args, const fs::path& out, size_t rows, int signal) {
  const pid_t child = startOntogen(args);
  EXPECT_GT(child, 0);
  if (child <= 0) return -1;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (std::chrono::steady_clock::now() < deadline &&
         lines(readWholeFile(out / "journal.jsonl")).size() < 1 + rows)
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  kill(child, signal);
  int status = 0;
  waitpid(child, &status, 0);
  return status;
}

// Killed midway (SIGKILL: nothing is written on the way out), a sweep resumes to the same
// bytes; stopped by Ctrl-C, it writes the table of what finished, in order, and exits 130.
TEST(SweepCli, KilledMidwayAndResumedGivesTheIdenticalTable) {
  const fs::path dir = scratchDir("sweep_resume");
  const fs::path tree = treeFile(dir);
  const std::string flags = " --define LEN=1,2,3 --define BRANCH=0.4,0.6 --seeds 1:3 --until 22 --size 32x32"
                            " --measure h=height --measure n=cells --workers 1";
  CliResult whole = runOntogen("sweep " + tree.string() + flags + " --out " + (dir / "whole").string());
  ASSERT_EQ(whole.exitCode, 0) << whole.err;
  const size_t allRows = 18;

  const fs::path cut = dir / "cut";
  const int status = signalledAfterRows(sweepArguments(tree, flags, cut), cut, 4, SIGKILL);
  const size_t journalLines = lines(readWholeFile(cut / "journal.jsonl")).size();
  ASSERT_GE(journalLines, 1u + 4) << "the sweep was killed before it journalled 4 rows";
  if (WIFSIGNALED(status) && journalLines < 1 + allRows) {
    EXPECT_FALSE(fs::exists(cut / "results.csv"));
  } else {  // it finished (or journalled its last row) before the kill
    cutAfter(cut, 4);
  }
  // What a kill leaves of a file being written: a temporary, which the resume removes.
  writeFile(cut / "thumbnails" / ".v0003.png.tmp999_1", "half a picture");

  // Without --resume the folder is refused; with it the rest runs.
  CliResult refused = runOntogen("sweep " + tree.string() + flags + " --out " + cut.string());
  EXPECT_EQ(refused.exitCode, 2);
  EXPECT_NE(refused.err.find("holds a sweep already (journal.jsonl); --resume continues it"), std::string::npos)
      << refused.err;
  std::string otherFlags = flags;
  otherFlags.replace(otherFlags.find("--seeds 1:3"), 11, "--seeds 1:2");
  CliResult other = runOntogen("sweep " + tree.string() + otherFlags + " --resume --out " + cut.string());
  EXPECT_EQ(other.exitCode, 2);
  EXPECT_NE(other.err.find("holds a sweep of other settings"), std::string::npos) << other.err;
  CliResult resumed = runOntogen("sweep " + tree.string() + flags + " --resume --out " + cut.string());
  ASSERT_EQ(resumed.exitCode, 0) << resumed.err;
  EXPECT_EQ(outputsOf(dir / "whole"), outputsOf(cut));
  EXPECT_EQ(lines(readWholeFile(cut / "journal.jsonl")).size(), 1u + allRows);
  EXPECT_FALSE(fs::exists(cut / "thumbnails" / ".v0003.png.tmp999_1"));

  // Ctrl-C stops cleanly: what finished is in the table, in order, and the exit code is
  // 130; a sweep that finished before the signal came exits 0 with the whole table.
  const fs::path stopped = dir / "stopped";
  const int stop = signalledAfterRows(sweepArguments(tree, flags, stopped), stopped, 2, SIGINT);
  ASSERT_TRUE(WIFEXITED(stop));
  const std::vector<std::string> partial = lines(readWholeFile(stopped / "results.csv"));
  const std::vector<std::string> full = lines(readWholeFile(dir / "whole" / "results.csv"));
  if (WEXITSTATUS(stop) == 0) {
    EXPECT_EQ(partial, full);
  } else {
    EXPECT_EQ(WEXITSTATUS(stop), 130);
    ASSERT_GE(partial.size(), 1u + 2);
    ASSERT_LT(partial.size(), full.size());
    for (size_t i = 0; i < partial.size(); ++i) EXPECT_EQ(partial[i], full[i]);  // rows 0, 1, ... in order
  }
}

TEST(SweepCli, AVariantPastMaxCellsIsAnErrorRow) {
  const fs::path dir = scratchDir("sweep_max_cells");
  const fs::path tree = treeFile(dir);
  CliResult result = runOntogen("sweep " + tree.string() +
                                " --define BRANCH=0,1 --define SHRINK=0.5 --size 16x16 --max-cells 100"
                                " --measure h=height --measure len=length --measure n=cells --out " +
                                (dir / "out").string());
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_NE(result.err.find("swept 2 variants (1 failed)"), std::string::npos) << result.err;
  const std::vector<std::string> table = lines(readWholeFile(dir / "out" / "results.csv"));
  ASSERT_EQ(table.size(), 3u);
  // The chain: 1 + 1/2 + 1/4 + 1/8 + 1/16 tall and long, A and 5 F.
  EXPECT_EQ(table[1], "0,0,0.5,1,1.9375,1.9375,6,");
  EXPECT_TRUE(table[2].starts_with("1,1,0.5,1,,,,")) << table[2];
  EXPECT_NE(table[2].find("--max-cells"), std::string::npos) << table[2];
  // The failed variant's tile is the warning colour; its program is written all the same.
  EXPECT_TRUE(fs::exists(dir / "out" / "programs" / "v0001.cell"));
  EXPECT_FALSE(fs::exists(dir / "out" / "thumbnails" / "v0001.png"));
  EXPECT_TRUE(fs::exists(dir / "out" / "thumbnails" / "v0000.png"));

  // A value the program does not take is an error row too, located in its lines.
  const fs::path step = writeFile(dir / "step.cell", "lsystem a {\n  #define D 1\n  #dt D\n  #until 3\n  axiom A\n"
                                                      "  A -> A F\n}\n");
  CliResult steps = runOntogen("sweep " + step.string() + " --define D=0,1 --size 16x16 --measure n=cells --out " +
                               (dir / "steps").string());
  ASSERT_EQ(steps.exitCode, 0) << steps.err;
  EXPECT_EQ(readWholeFile(dir / "steps" / "results.csv"),
            "variant,D,seed,n,error\n0,0,1,," + step.string() +
                ":3:3: #dt must be a finite number greater than 0\n1,1,1,4,\n");
}

// `ontogen ARGS` in a pseudo-terminal (util-linux's script), as a user at a terminal runs
// it: everything it printed to stdout and stderr, as the terminal received it.
std::string inATerminal(const std::string& args) {
  return runOntogenShell(args + "\" /dev/null </dev/null 2>&1", "timeout 60 script -qec \"").out;
}

// The bar's drawings in `text` (each begins with a carriage return and the label): the
// count done of each, in order.
std::vector<std::pair<long, long>> barCounts(const std::string& text, const std::string& label) {
  std::vector<std::pair<long, long>> counts;
  for (size_t at = text.find("\r" + label + " ["); at != std::string::npos;
       at = text.find("\r" + label + " [", at + 1)) {
    const size_t count = text.find("] ", at) + 2;
    long done = 0, total = 0;
    if (std::sscanf(text.c_str() + count, "%ld/%ld", &done, &total) == 2) counts.emplace_back(done, total);
  }
  return counts;
}

// The bar counts variants done, failures and time left; it is drawn at a terminal, not
// into a file unless asked (--progress), never when told not to (--no-progress), and
// across MPI ranks once, by rank 0, when asked.
TEST(SweepCli, TheProgressBarCountsVariantsFailuresAndTimeLeft) {
  const fs::path dir = scratchDir("sweep_progress");
  const fs::path tree = treeFile(dir);
  const std::string flags = " --define BRANCH=0,1 --define SHRINK=0.5,0.6 --size 16x16 --max-cells 100";

  const std::string terminal = inATerminal("sweep " + tree.string() + flags + " --out " + (dir / "tty").string());
  const auto drawn = barCounts(terminal, "sweeping tree");
  ASSERT_FALSE(drawn.empty()) << terminal;
  EXPECT_EQ(drawn.back(), std::make_pair(4L, 4L)) << terminal;
  EXPECT_NE(terminal.find("4/4, 2 failed, 0 s left"), std::string::npos) << terminal;
  for (size_t i = 1; i < drawn.size(); ++i) EXPECT_GE(drawn[i].first, drawn[i - 1].first) << terminal;
  EXPECT_NE(terminal.find("swept 4 variants (2 failed)"), std::string::npos) << terminal;

  const std::string told = inATerminal("sweep " + tree.string() + flags + " --no-progress --out " +
                                       (dir / "quiet").string());
  EXPECT_TRUE(barCounts(told, "sweeping tree").empty()) << told;
  EXPECT_NE(told.find("swept 4 variants (2 failed)"), std::string::npos) << told;

  CliResult file = runOntogen("sweep " + tree.string() + flags + " --out " + (dir / "file").string());
  ASSERT_EQ(file.exitCode, 0) << file.err;
  EXPECT_TRUE(barCounts(file.err, "sweeping tree").empty()) << file.err;
  CliResult asked = runOntogen("sweep " + tree.string() + flags + " --progress --out " + (dir / "asked").string());
  ASSERT_EQ(asked.exitCode, 0) << asked.err;
  EXPECT_EQ(barCounts(asked.err, "sweeping tree").back(), std::make_pair(4L, 4L)) << asked.err;

  CliResult evolve = runOntogen("evolve " + tree.string() + " --range LEN=1:2 --population 4 --generations 2 "
                                "--measure h=height --size 16x16 --progress --out " +
                                (dir / "evolve").string());
  ASSERT_EQ(evolve.exitCode, 0) << evolve.err;
  EXPECT_EQ(barCounts(evolve.err, "evolving tree, generation 2/2").back(), std::make_pair(4L, 4L)) << evolve.err;

  ONTOGEN_REQUIRE_MPI();
  const fs::path log = dir / "mpi_out.txt";
  ASSERT_EQ(runOnThreeRanks("sweep " + tree.string() + flags + " --workers 1 --progress --out " +
                                (dir / "ranks").string(),
                            log),
            0)
      << readWholeFile(log);
  const std::string ranks = readWholeFile(log);
  const auto counts = barCounts(ranks, "sweeping tree");
  ASSERT_FALSE(counts.empty()) << ranks;
  EXPECT_EQ(counts.back(), std::make_pair(4L, 4L)) << ranks;
  // One bar: a bar per rank would count its own variants from 1 again.
  for (size_t i = 1; i < counts.size(); ++i) EXPECT_GT(counts[i].first, counts[i - 1].first) << ranks;
}

std::vector<std::string> fieldsOf(const std::string& row) {
  std::vector<std::string> fields;
  std::istringstream in(row);
  for (std::string field; std::getline(in, field, ',');) fields.push_back(field);
  return fields;
}

// The physics and creature sets' quantities against closed forms: models/cantilever.cell
// is weightless with a tip load P on an arm of L = 1 m, so its root carries |F| = P and
// |M| = P L (a hair less: the arm bends), and its tip sinks P L^3 / (3 EI) = P / 3000 m;
// models/creature.cell walks STRIDE / (DUTY PERIOD) = 0.55 / 0.6 units a second with its
// stance feet planted (the creature tests: they do not move at all).
TEST(SweepCli, PhysicsAndCreatureMeasuresByTheirClosedForms) {
  const fs::path dir = scratchDir("sweep_sets");
  CliResult rods = runOntogen("sweep " + modelPath("cantilever.cell") +
                              " --define P=1,2 --size 16x16 --measure m=root_moment --measure f=root_force"
                              " --measure d=deflection --measure r=rods --out " + (dir / "rods").string());
  ASSERT_EQ(rods.exitCode, 0) << rods.err;
  const std::vector<std::string> table = lines(readWholeFile(dir / "rods" / "results.csv"));
  ASSERT_EQ(table.size(), 3u);
  for (int p = 1; p <= 2; ++p) {
    const std::vector<std::string> row = fieldsOf(table[p]);
    ASSERT_EQ(row.size(), 7u) << table[p];
    EXPECT_NEAR(std::stod(row[3]), p * 1.0, 1e-6 * p) << table[p];
    EXPECT_LT(std::stod(row[3]), p * 1.0);
    EXPECT_EQ(std::stod(row[4]), p * 1.0);
    EXPECT_NEAR(std::stod(row[5]), p / 3000.0, 1e-3 * p / 3000.0) << table[p];
    EXPECT_EQ(row[6], "10");
  }

  CliResult walk = runOntogen("sweep " + modelPath("creature.cell") +
                              " --define SEGMENTS=2 --define NOISE=0,0.15 --size 16x16 --measure d=distance"
                              " --measure s=slip --measure t=time --out " + (dir / "walk").string());
  ASSERT_EQ(walk.exitCode, 0) << walk.err;
  const std::vector<std::string> walked = lines(readWholeFile(dir / "walk" / "results.csv"));
  ASSERT_EQ(walked.size(), 3u);
  for (int v = 1; v <= 2; ++v) {
    const std::vector<std::string> row = fieldsOf(walked[v]);
    ASSERT_EQ(row.size(), 7u) << walked[v];
    EXPECT_NEAR(std::stod(row[4]), 0.55 / 0.6 * std::stod(row[6]), 1e-9) << walked[v];
    EXPECT_LT(std::stod(row[5]), 1e-9) << walked[v];
  }
  // A measure of a set the variants do not run is refused before anything runs.
  CliResult noSet = runOntogen("sweep " + modelPath("cantilever.cell") + " --interpret geometry --measure s=slip --out " +
                               (dir / "none").string());
  EXPECT_EQ(noSet.exitCode, 2);
  EXPECT_EQ(noSet.err, "ontogen: error: --measure s reads what the creature set reports, and the variants run no "
                       "creature set (add --interpret creature, or #interpret in the program)\n");
  EXPECT_FALSE(fs::exists(dir / "none"));
}

TEST(SweepCli, BadFlagsAreUsageErrors) {
  const fs::path dir = scratchDir("sweep_bad");
  const fs::path tree = treeFile(dir);
  const std::string head = "sweep " + tree.string() + " --out " + (dir / "out").string();
  struct Case {
    std::string flags, message;
  };
  const std::vector<Case> cases{
      {" --define LEN=1:2", "--define LEN=1:2: '1:2' is not A:B:N"},
      {" --define LEN=1:2:0", "N must be a whole number from 1 to"},
      {" --define LEN=1,x", "'x' is not a number"},
      {" --define NOPE=1,2", "the program has no #define NOPE whose value is a number"},
      {" --seeds 4:1", "--seeds takes S1:S2"},
      {" --measure h=hieght", "--measure h: unknown quantity 'hieght'"},
      {" --measure h=height+", "expected a number, a quantity or '(' at column 8 of 'height+'"},
      {" --measure m=root_moment", "--measure m reads what the physics set reports"},
      {" --interpret music --measure h=height", "--measure h reads the bounding box of what the sets draw"},
      {" --measure seed=cells", "the name of another column"},
  };
  for (const Case& c : cases) {
    CliResult result = runOntogen(head + c.flags);
    EXPECT_EQ(result.exitCode, 2) << c.flags;
    EXPECT_NE(result.err.find(c.message), std::string::npos) << c.flags << ": " << result.err;
  }
}

// Evolution: the same seeds give the same generations byte for byte, and a fitness that
// rewards height grows taller trees (the elite keep the best, so it never falls).
TEST(EvolveCli, ReproducibleAndRewardingHeightGrowsTallerTrees) {
  const fs::path dir = scratchDir("evolve");
  const fs::path tree = treeFile(dir);
  const std::string flags = " --generations 10 --population 8 --elite 2 --evolve-seed 5 --size 24x24"
                            " --measure tall=height --measure n=cells";
  CliResult first = runOntogen("evolve " + tree.string() + flags + " --out " + (dir / "a").string());
  ASSERT_EQ(first.exitCode, 0) << first.err;
  CliResult second = runOntogen("evolve " + tree.string() + flags + " --workers 1 --out " + (dir / "b").string());
  ASSERT_EQ(second.exitCode, 0) << second.err;
  for (int g = 0; g < 10; ++g) {
    const std::string name = "generation_00" + std::to_string(g);
    EXPECT_EQ(outputsOf(dir / "a" / name), outputsOf(dir / "b" / name)) << name;
  }
  EXPECT_EQ(readWholeFile(dir / "a" / "evolution.csv"), readWholeFile(dir / "b" / "evolution.csv"));
  EXPECT_EQ(readWholeFile(dir / "a" / "best.cell"), readWholeFile(dir / "b" / "best.cell"));

  const std::vector<std::string> summary = lines(readWholeFile(dir / "a" / "evolution.csv"));
  ASSERT_EQ(summary.size(), 11u);
  EXPECT_EQ(summary[0], "generation,best_variant,best_tall,mean_tall,failed");
  std::vector<double> best;
  for (size_t g = 1; g < summary.size(); ++g) {
    std::istringstream row(summary[g]);
    std::string field;
    for (int column = 0; column < 3; ++column) std::getline(row, field, ',');
    best.push_back(std::stod(field));
  }
  for (size_t g = 1; g < best.size(); ++g) EXPECT_GE(best[g], best[g - 1]) << "generation " << g;
  EXPECT_GT(best.back(), 1.5 * best.front());
  // The first generation's first variant is the program as written.
  const std::vector<std::string> first0 = lines(readWholeFile(dir / "a" / "generation_000" / "results.csv"));
  EXPECT_EQ(first0[0], "variant,LEN,SHRINK,BRANCH,seed,tall,n,error");
  EXPECT_TRUE(first0[1].starts_with("0,1,0.8,0.5,1,")) << first0[1];
  // BRANCH keeps to the program's #range 0 1 however it mutates.
  for (int g = 0; g < 10; ++g)
    for (const std::string& row : lines(readWholeFile(dir / "a" / ("generation_00" + std::to_string(g)) / "results.csv"))) {
      if (row.starts_with("variant")) continue;
      std::istringstream fields(row);
      std::string field;
      for (int column = 0; column < 4; ++column) std::getline(fields, field, ',');
      EXPECT_LE(std::stod(field), 1.0) << row;
    }
  // The best program grows as tall alone as its row says.
  EXPECT_TRUE(fs::exists(dir / "a" / "gallery.png"));
  EXPECT_TRUE(fs::exists(dir / "a" / "best" / "generation_009.cell"));
  // The galleries label each tile with its genes as the table writes them; the gallery
  // of the best, with its generation too.
  const nlohmann::json generation0 = nlohmann::json::parse(readWholeFile(dir / "a" / "generation_000" / "gallery.json"));
  ASSERT_EQ(generation0["tiles"].size(), 8u);
  EXPECT_EQ(generation0["tiles"][0]["label"], "LEN=1 SHRINK=0.8 BRANCH=0.5");
  EXPECT_GT(generation0["pixels_per_unit"].get<double>(), 0);
  const nlohmann::json bests = nlohmann::json::parse(readWholeFile(dir / "a" / "gallery.json"));
  ASSERT_EQ(bests["tiles"].size(), 10u);
  const size_t bestVariant = std::stoul(after(summary[10], 1));
  std::istringstream bestRow(lines(readWholeFile(dir / "a" / "generation_009" / "results.csv"))[bestVariant + 1]);
  std::string len, shrink, branch;
  for (std::string* field : {&len, &len, &shrink, &branch}) std::getline(bestRow, *field, ',');
  EXPECT_EQ(bests["tiles"][9]["label"], "G9 LEN=" + len + " SHRINK=" + shrink + " BRANCH=" + branch);
}

// An evolution stopped in its third generation (a journal cut mid-line, the fourth never
// begun) resumes to the same generations, best program and summary; so does one on three
// MPI ranks.
TEST(EvolveCli, ResumedOrOnThreeRanksGivesTheSameGenerations) {
  const fs::path dir = scratchDir("evolve_resume");
  const fs::path tree = treeFile(dir);
  const std::string flags = " --generations 4 --population 6 --evolve-seed 9 --size 16x16 --measure tall=height";
  CliResult whole = runOntogen("evolve " + tree.string() + flags + " --out " + (dir / "whole").string());
  ASSERT_EQ(whole.exitCode, 0) << whole.err;
  fs::copy(dir / "whole", dir / "cut", fs::copy_options::recursive);
  const fs::path journal = dir / "cut" / "generation_002" / "journal.jsonl";
  const std::vector<std::string> rows = lines(readWholeFile(journal));
  ASSERT_EQ(rows.size(), 7u);
  writeFile(journal, rows[0] + "\n" + rows[1] + "\n" + rows[2] + "\n" + rows[3].substr(0, 10));
  for (const char* gone : {"generation_003", "best", "best.cell", "evolution.csv", "gallery.png"})
    fs::remove_all(dir / "cut" / gone);
  for (const char* gone : {"results.csv", "results.json", "gallery.png"})
    fs::remove(dir / "cut" / "generation_002" / gone);

  CliResult refused = runOntogen("evolve " + tree.string() + flags + " --out " + (dir / "cut").string());
  EXPECT_EQ(refused.exitCode, 2) << refused.err;
  CliResult resumed = runOntogen("evolve " + tree.string() + flags + " --resume --out " + (dir / "cut").string());
  ASSERT_EQ(resumed.exitCode, 0) << resumed.err;
  for (int g = 0; g < 4; ++g) {
    const std::string name = "generation_00" + std::to_string(g);
    EXPECT_EQ(outputsOf(dir / "whole" / name), outputsOf(dir / "cut" / name)) << name;
  }
  EXPECT_EQ(lines(readWholeFile(journal)).size(), 7u);
  for (const char* file : {"best.cell", "evolution.csv", "gallery.png", "best/generation_003.cell"})
    EXPECT_EQ(readWholeFile(dir / "whole" / file), readWholeFile(dir / "cut" / file)) << file;

  // Three ranks breed the same generations: each chooses from the table rank 0 sends.
  ONTOGEN_REQUIRE_MPI();
  ASSERT_EQ(runOnThreeRanks("evolve " + tree.string() + flags + " --workers 1 --out " + (dir / "ranks").string(),
                            dir / "mpi_out.txt"),
            0)
      << readWholeFile(dir / "mpi_out.txt");
  for (int g = 0; g < 4; ++g) {
    const std::string name = "generation_00" + std::to_string(g);
    EXPECT_EQ(outputsOf(dir / "whole" / name), outputsOf(dir / "ranks" / name)) << name;
  }
  for (const char* file : {"best.cell", "evolution.csv", "gallery.png"})
    EXPECT_EQ(readWholeFile(dir / "whole" / file), readWholeFile(dir / "ranks" / file)) << file;
}

}  // namespace
}  // namespace ontogen::test
