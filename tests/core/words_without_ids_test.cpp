// Words rewritten by a table grow without their ids (docs/COMPACT_WORDS.md, "Words
// without ids"), and a reader sees the ids the development gives when it keeps them: the
// pool replays the rewrites from the last word that held its ids (core/table_replay.h).

#include <gtest/gtest.h>

#include <bit>
#include <limits>
#include <span>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "core/parallel_rewrite.h"
#include "core/word.h"
#include "core/world.h"
#include "interpreters/text/word_text.h"
#include "test_support.h"

namespace ontogen {
namespace {

// A timed word by a table: F and G expire at different instants (their successors are
// born at their deaths, which fall between the steps' ends), H is renewed every 2.5 s, I
// never expires and is kept with its birth. Large enough for slices from t = 5 on.
std::string timedTable() {
  std::string axiom;
  for (int i = 0; i < 40'000; ++i) axiom += i % 7000 == 4 ? "F G I " : i % 3 ? "H " : "I ";
  return "cell F { lifetime 1; rules { terminal: -> F G F F I; } }\n"
         "cell G { lifetime 3.25; rules { terminal: -> H F H H G H H F H H H H H H H H H H H; } }\n"
         "cell H { lifetime 2.5; }\n"
         "cell I { }\n"
         "system s { pool linear; axiom " +
         axiom + "; }\n";
}

const char* kKoch = R"(lsystem koch {
  axiom F
  F -> F + F - F - F + F
})";

// The strategies that rewrote the word and how often (core/rewrite_plan.h), as --stats
// prints them.
std::string ran(const World& world) {
  return formatRewriteCounts(world.stats().rewrites);
}

World growing(const std::shared_ptr<const Program>& program, unsigned threads, bool withoutIds) {
  WorldDef def;
  def.seed = 5;
  def.threads = threads;
  def.wordsWithoutIds = withoutIds;
  return World(program, def);
}

// The cells, read through a cursor and by index, as every reader reads them.
void expectSameCells(const Pool& expected, const Pool& actual, const std::string& what) {
  ASSERT_EQ(expected.size(), actual.size()) << what;
  for (CellCursor x = expected.cursor(), y = actual.cursor(); !x.done(); x.next(), y.next())
    ASSERT_TRUE(x.master() == y.master() && x.id() == y.id() &&
                std::bit_cast<uint64_t>(x.birth()) == std::bit_cast<uint64_t>(y.birth()))
        << what << ": cell " << x.index();
  for (size_t i = 0; i < expected.size(); i += 97) ASSERT_EQ(expected.cellAt(i).id, actual.cellAt(i).id) << what;
}

// The word held without ids, before anyone reads its ids: its labels, and the birth of
// each module that can expire found through the block index (CompactWord::locate), as the
// next rewrite finds it. A timeless module (lifetime forever) keeps no birth of its own
// there: it joins the run beside it. Returns how many modules were timeless.
size_t expectSameLabelsAndBirths(const Program& program, const Pool& expected, const Pool& withoutIds,
                                 const std::string& what) {
  EXPECT_FALSE(withoutIds.holdsIds()) << what;
  const CompactWord& word = withoutIds.compactWord();
  EXPECT_EQ(expected.size(), word.size()) << what;
  if (expected.size() != word.size()) return 0;
  size_t timeless = 0;
  for (CellCursor x = expected.cursor(); !x.done(); x.next()) {
    const size_t i = x.index();
    const uint32_t label = word.label(i);
    EXPECT_EQ(x.master(), label) << what << ": module " << i;
    if (x.master() != label) return timeless;
    if (program.masters[label].lifetime == std::numeric_limits<double>::infinity()) {
      ++timeless;
      continue;
    }
    const uint64_t expectedBirth = std::bit_cast<uint64_t>(x.birth());
    const uint64_t heldBirth = std::bit_cast<uint64_t>(word.birthOf(word.locate(i).run));
    EXPECT_EQ(expectedBirth, heldBirth) << what << ": module " << i;
    if (expectedBirth != heldBirth) return timeless;
  }
  EXPECT_FALSE(withoutIds.holdsIds()) << what << ": nothing above reads an id";
  return timeless;
}

TEST(WordsWithoutIds, ATimedWordReadsAsTheWordGrownWithIdsOnEveryThreadCount) {
  auto program = testing_support::compileOrFail(timedTable());
  ASSERT_NE(program, nullptr);
  ASSERT_TRUE(ParallelRewrite(*program, program->systems[program->root]).rewritesByTable());
  World reference = growing(program, 1, false);
  reference.advanceTo(9, 1.0);
  ASSERT_GT(reference.rootPool().size(), 200'000u);
  ASSERT_TRUE(reference.rootPool().holdsIds());
  EXPECT_EQ(ran(reference), "table-alone 23");
  for (unsigned threads : {1u, 2u, 3u}) {
    World world = growing(program, threads, true);
    world.advanceTo(9, 1.0);
    const Pool& pool = world.rootPool();
    ASSERT_TRUE(pool.holdsCompactWord());
    EXPECT_FALSE(pool.holdsIds()) << threads << " threads";
    EXPECT_EQ(ran(world), threads == 1 ? "table-alone 23" : "compact-slices 23") << threads << " threads";
    // Runs split where the birth changes, not at every event, and keep no key.
    EXPECT_LT(pool.compactWord().runCount(), reference.rootPool().compactWord().runCount()) << threads << " threads";
    EXPECT_LT(pool.bytes(), reference.rootPool().bytes() / 2) << threads << " threads";
    EXPECT_TRUE(pool.compactWord().indexAgrees()) << threads << " threads";
    EXPECT_EQ(world.stats().events, reference.stats().events);
    EXPECT_EQ(world.stats().cellsBorn, reference.stats().cellsBorn);
    EXPECT_GT(expectSameLabelsAndBirths(*program, reference.rootPool(), pool, std::to_string(threads) + " threads"), 0u);
    expectSameCells(reference.rootPool(), pool, std::to_string(threads) + " threads");
    EXPECT_TRUE(pool.holdsIds()) << "read once, the ids are held";
  }
}

// Read in the middle of the growth, the word takes its ids back and becomes the anchor of
// the words after it; a copy of a world shares its replay and reads the same.
TEST(WordsWithoutIds, AWordReadOnTheWayAndACopyReadAsTheWordGrownWithIds) {
  auto program = testing_support::compileOrFail(timedTable());
  ASSERT_NE(program, nullptr);
  World reference = growing(program, 2, false);
  World world = growing(program, 2, true);
  for (double t : {3.0, 6.5, 8.0}) {
    reference.advanceTo(t, 1.0);
    world.advanceTo(t, 1.0);
    EXPECT_GT(expectSameLabelsAndBirths(*program, reference.rootPool(), world.rootPool(), "t = " + std::to_string(t)), 0u)
        << "I is timeless";
    World copy = world;
    EXPECT_FALSE(copy.rootPool().holdsIds()) << t;
    expectSameCells(reference.rootPool(), copy.rootPool(), "the copy at t = " + std::to_string(t));
    EXPECT_FALSE(world.rootPool().holdsIds()) << "the copy read its own word";
    expectSameCells(reference.rootPool(), world.rootPool(), "t = " + std::to_string(t));
  }
}

// A copy made while the word is held without ids shares the replay's instants; the world
// and the copy then grow on apart, each appending its own (the copy's first rewrite finds
// the world's already there and takes its own list), and each reads as the word grown
// with ids, unread until the end.
TEST(WordsWithoutIds, AWorldAndItsCopyGrowingApartReadAsTheWordGrownWithIds) {
  auto program = testing_support::compileOrFail(timedTable());
  ASSERT_NE(program, nullptr);
  World reference = growing(program, 1, false);
  World world = growing(program, 1, true);
  world.advanceTo(3, 1.0);
  ASSERT_FALSE(world.rootPool().holdsIds());
  World copy = world;
  world.advanceTo(5, 1.0);
  copy.advanceTo(4, 1.0);
  copy.advanceTo(6, 1.0);
  world.advanceTo(6, 1.0);
  reference.advanceTo(6, 1.0);
  ASSERT_FALSE(world.rootPool().holdsIds());
  ASSERT_FALSE(copy.rootPool().holdsIds());
  expectSameCells(reference.rootPool(), copy.rootPool(), "the copy");
  expectSameCells(reference.rootPool(), world.rootPool(), "the world");
}

// Every module of Thue-Morse expires at every step, so a step's word is one run a slice:
// slices placed by bounds (a run a module) close the gaps between their runs. Its labels
// share one lifetime, so a run goes by the walk's loop of a copy a module.
TEST(WordsWithoutIds, ThueMorseBySlicesTakesARunASlice) {
  auto program = testing_support::compileOrFail(testing_support::kThueMorse);
  ASSERT_NE(program, nullptr);
  World reference = growing(program, 1, false);
  reference.advanceTo(18, 1.0);
  ASSERT_EQ(reference.rootPool().size(), 262'144u);
  for (unsigned threads : {1u, 2u, 3u}) {
    World world = growing(program, threads, true);
    for (int t = 1; t <= 18; ++t) {  // each word's block index, as the next rewrite reads it
      world.advanceTo(t, 1.0);
      ASSERT_TRUE(world.rootPool().compactWord().indexAgrees()) << threads << " threads, t = " << t;
    }
    EXPECT_EQ(ran(world), threads == 1 ? "table-alone 18" : "table-alone 15, table-bounds 3") << threads << " threads";
    EXPECT_LE(world.rootPool().compactWord().runCount(), 4u * threads) << threads << " threads";
    EXPECT_TRUE(world.rootPool().compactWord().indexAgrees()) << threads << " threads";
    EXPECT_EQ(world.stats().events, reference.stats().events) << threads << " threads";
    EXPECT_EQ(world.stats().cellsBorn, reference.stats().cellsBorn) << threads << " threads";
    expectSameLabelsAndBirths(*program, reference.rootPool(), world.rootPool(), std::to_string(threads) + " threads");
    expectSameCells(reference.rootPool(), world.rootPool(), std::to_string(threads) + " threads");
  }
}

// Readers on several threads at once: one replays, the others wait for it.
TEST(WordsWithoutIds, ReadersOnSeveralThreadsSeeTheSameIds) {
  auto program = testing_support::compileOrFail(kKoch);
  ASSERT_NE(program, nullptr);
  World reference = growing(program, 1, false);
  reference.advanceTo(8, 1.0);
  World world = growing(program, 2, true);
  world.advanceTo(8, 1.0);
  EXPECT_GT(expectSameLabelsAndBirths(*program, reference.rootPool(), world.rootPool(), "Koch on two threads"), 0u);
  std::vector<uint64_t> sums(4, 0);
  std::vector<std::thread> readers;
  for (size_t r = 0; r < sums.size(); ++r)
    readers.emplace_back([&, r] {
      for (CellCursor cell = world.rootPool().cursor(r * 1000); !cell.done(); cell.next()) sums[r] ^= cell.id();
    });
  for (std::thread& reader : readers) reader.join();
  for (size_t r = 0; r < sums.size(); ++r) {
    uint64_t expected = 0;
    for (CellCursor cell = reference.rootPool().cursor(r * 1000); !cell.done(); cell.next()) expected ^= cell.id();
    EXPECT_EQ(sums[r], expected) << "reader " << r;
  }
}

// Koch holds little more than a byte a module without ids (its label, a bit and the block
// index): its turns never expire, so they join the run of the F beside them, and a step's
// word is a run a chunk of the walk. A cell limit stops it as it stops the word with ids.
TEST(WordsWithoutIds, KochTakesAByteAModuleAndALimitStopsItAsBefore) {
  auto program = testing_support::compileOrFail(kKoch);
  ASSERT_NE(program, nullptr);
  World world = growing(program, 1, true);
  for (int t = 1; t <= 8; ++t) {
    world.advanceTo(t, 1.0);
    ASSERT_TRUE(world.rootPool().compactWord().indexAgrees()) << "t = " << t;
  }
  const Pool& pool = world.rootPool();
  ASSERT_EQ(pool.size(), 781'249u);
  ASSERT_FALSE(pool.holdsIds());
  // With ids: a run for the new successors of each F and one for each turn kept (156,249).
  EXPECT_LE(pool.compactWord().runCount(), 16u);
  EXPECT_TRUE(pool.compactWord().indexAgrees());
  EXPECT_LT(static_cast<double>(pool.bytes()) / static_cast<double>(pool.size()), 1.25);
  std::string messages[2];
  for (const bool withoutIds : {false, true}) {
    WorldDef def;
    def.wordsWithoutIds = withoutIds;
    def.limits.maxCells = 1'000'000;
    World limited(program, def);
    try {
      limited.advanceTo(10, 1.0);
      ADD_FAILURE() << "no limit";
    } catch (const LimitError& error) {
      messages[withoutIds] = error.what();
    }
  }
  EXPECT_EQ(messages[0], messages[1]);
  EXPECT_NE(messages[0].find("1000000 cells"), std::string::npos) << messages[0];
}

// A timed word with state values by a table: each successor's value is one operation on
// the cell's own values (every kind: a constant, a copy, x + c, c + x, x - c, c - x,
// x * c, c * x, x / c, c / x), F and G expire at different instants, H is renewed with its
// value, I keeps two values and never expires, C is a renewed module without values.
std::string timedTableWithValues() {
  std::string axiom;
  for (int i = 0; i < 40'000; ++i) axiom += i % 7000 == 4 ? "F(1, 2) G(0.5) I(3, 4) " : i % 3 ? "H(0.75) " : "I(1, 2) ";
  // 6 / g divides by a g of 0 on the way: the infinity is part of what must match.
  return "#allow nonfinite\n"
         "cell F(x = 1, y = 2) { lifetime 1;\n"
         "  rules { terminal: -> F(x + 1, y) G(x * 0.5) F(3 - x, y / 4) C I(y - 0.25, 7); } }\n"
         "cell G(g = 0) { lifetime 3.25;\n"
         "  rules { terminal: -> H(g) F(g / 3, 1.5 * g) G(2 + g) H(0 - g) H(6 / g) C C H(g) H(g) H(g)\n"
         "                       H(g) H(g) H(g) H(g) H(g) H(g) H(g) H(g) H(g); } }\n"
         "cell H(h = 0) { lifetime 2.5; }\n"
         "cell I(a = 0, b = 0) { }\n"
         "cell C { lifetime 2; }\n"
         "system s { pool linear; axiom " +
         axiom + "; }\n";
}

void expectSameValues(std::span<const double> expected, std::span<const double> actual, const std::string& what) {
  ASSERT_EQ(expected.size(), actual.size()) << what;
  for (size_t v = 0; v < expected.size(); ++v)
    ASSERT_EQ(std::bit_cast<uint64_t>(expected[v]), std::bit_cast<uint64_t>(actual[v])) << what << ": value " << v;
}

// The values a word without ids holds are those the records' serial pass computes (the
// next rewrite reads them before any id is replayed), and the replay gives every cell its
// id, birth and values, on every thread count. Arguments that are not one operation on
// the cell's values keep the batch interpreter.
TEST(WordsWithoutIds, AWordWithValuesComputesThemAsTheInterpreterDoes) {
  auto program = testing_support::compileOrFail(timedTableWithValues());
  ASSERT_NE(program, nullptr);
  ASSERT_TRUE(ParallelRewrite(*program, program->systems[program->root]).rewritesByTable());
  WorldDef serialDef;
  serialDef.seed = 5;
  serialDef.rewriteBySlices = false;  // the records' pass, with the expression interpreter
  World reference(program, serialDef);
  reference.advanceTo(12, 1.0);
  ASSERT_GT(reference.rootPool().size(), 200'000u);
  World withIds = growing(program, 2, false);
  withIds.advanceTo(12, 1.0);
  for (unsigned threads : {1u, 2u, 3u}) {
    const std::string what = std::to_string(threads) + " threads";
    World world = growing(program, threads, true);
    world.advanceTo(12, 1.0);
    const Pool& pool = world.rootPool();
    ASSERT_TRUE(pool.holdsCompactWord()) << what;
    EXPECT_FALSE(pool.holdsIds()) << what;
    EXPECT_EQ(ran(world), threads == 1 ? "table-alone 35" : "compact-slices 35") << what;
    EXPECT_TRUE(pool.compactWord().indexAgrees()) << what;
    EXPECT_EQ(world.stats().events, reference.stats().events) << what;
    EXPECT_EQ(world.stats().cellsBorn, reference.stats().cellsBorn) << what;
    expectSameValues(reference.rootPool().stateArena(), pool.compactWord().values(), what + ", held without ids");
    EXPECT_GT(expectSameLabelsAndBirths(*program, withIds.rootPool(), pool, what), 0u) << "I is timeless";
    expectSameCells(reference.rootPool(), pool, what);
    expectSameValues(reference.rootPool().stateArena(), pool.stateArena(), what + ", replayed");
    for (size_t i = 0; i < pool.size(); i += 101)
      ASSERT_EQ(reference.rootPool().stateOffset(i), pool.stateOffset(i)) << what << ": cell " << i;
  }
  expectSameCells(reference.rootPool(), withIds.rootPool(), "grown with ids");
  expectSameValues(reference.rootPool().stateArena(), withIds.rootPool().stateArena(), "grown with ids");

  // The benchmark's parametric system goes by the table too; an argument of two values,
  // a negation, the age or a function does not.
  auto parametric = testing_support::compileOrFail(testing_support::kParametric);
  ASSERT_NE(parametric, nullptr);
  EXPECT_TRUE(ParallelRewrite(*parametric, parametric->systems[parametric->root]).rewritesByTable());
  for (const char* argument : {"x * x", "-x", "x + age", "sqrt(x)", "x * 2 + 1"}) {
    auto model = testing_support::compileOrFail(std::string("lsystem p {\n  axiom A(1)\n  A(x) -> A(") + argument +
                                                ") A(x)\n}\n");
    ASSERT_NE(model, nullptr) << argument;
    EXPECT_FALSE(ParallelRewrite(*model, model->systems[model->root]).rewritesByTable()) << argument;
  }
}

// Modules of one value that follow one another go by the loop of multiply-adds, for one
// to four values written (D renewed: one; A: two; B, with a module without values among
// its successors: three; C: four). Each step's values, held without ids and read by the
// next step before any id is replayed, are those the interpreter computes.
TEST(WordsWithoutIds, ModulesOfOneValueComputeTheirSuccessorsValuesAsTheInterpreterDoes) {
  auto program = testing_support::compileOrFail(
      "cell A(x = 1) { lifetime 1; rules { terminal: -> A(x + 1) B(x * 0.5); } }\n"
      "cell B(y = 0) { lifetime 1; rules { terminal: -> B(y + 1) S C(y * 0.5) B(2 - y); } }\n"
      "cell C(z = 0) { lifetime 1; rules { terminal: -> C(z * 3) B(z - 1) C(0.25 * z) D(z + 0.5) D(z); } }\n"
      "cell D(w = 0) { lifetime 1; }\n"
      "cell S { lifetime 1; }\n"
      "system s { pool linear; axiom A(1) D(7) B(0.5); }\n");
  ASSERT_NE(program, nullptr);
  ASSERT_TRUE(ParallelRewrite(*program, program->systems[program->root]).rewritesByTable());
  WorldDef serialDef;
  serialDef.seed = 5;
  serialDef.rewriteBySlices = false;
  for (unsigned threads : {1u, 2u, 3u}) {
    World reference(program, serialDef);
    World world = growing(program, threads, true);
    for (int t = 1; t <= 10; ++t) {
      const std::string what = std::to_string(threads) + " threads, t = " + std::to_string(t);
      reference.advanceTo(t, 1.0);
      world.advanceTo(t, 1.0);
      ASSERT_FALSE(world.rootPool().holdsIds()) << what;
      ASSERT_TRUE(world.rootPool().compactWord().indexAgrees()) << what;
      expectSameValues(reference.rootPool().stateArena(), world.rootPool().compactWord().values(), what);
    }
    EXPECT_GT(world.rootPool().size(), 4 * ParallelRewrite::kMinimumCells);
    EXPECT_EQ(ran(world), threads == 1 ? "table-alone 10" : "table-alone 9, table-bounds 1") << threads << " threads";
    expectSameCells(reference.rootPool(), world.rootPool(), std::to_string(threads) + " threads");
  }
}

// The word as text, as `ontogen word` streams it.
std::string wordText(const World& world, bool interpreted) {
  std::ostringstream text;
  {
    BufferedOutput out(text);
    WordTextWriter writer(out, 9);
    if (interpreted)
      visitInterpretedWord(world, writer);
    else
      visitWord(world, writer);
  }
  return text.str();
}

// The text of a word reads labels, values and the ages of timed modules alone: a word held
// without ids is written as it is held, without the replay of its ids, and reads as the
// word grown by the records' pass. Timed modules take their ages from their runs' births.
TEST(WordsWithoutIds, TheWordAsTextIsWrittenWithoutMakingItsIdsAgain) {
  for (const std::string& text : {std::string(testing_support::kParametric), timedTableWithValues()}) {
    auto program = testing_support::compileOrFail(text);
    ASSERT_NE(program, nullptr);
    WorldDef serialDef;
    serialDef.seed = 5;
    serialDef.rewriteBySlices = false;
    World reference(program, serialDef);
    World world = growing(program, 2, true);
    for (double t : {6.0, 8.5}) {
      const std::string what = program->systems[program->root].name + " at t = " + std::to_string(t);
      reference.advanceTo(t, 1.0);
      world.advanceTo(t, 1.0);
      ASSERT_FALSE(world.rootPool().holdsIds()) << what;
      const std::string expected = formatWord(captureWord(reference), 9);
      EXPECT_EQ(wordText(world, false), expected) << what;
      EXPECT_EQ(wordText(world, true), expected) << what << ", interpreted";
      EXPECT_FALSE(world.rootPool().holdsIds()) << what << ": the text read no id";
    }
    EXPECT_NE(formatWord(captureWord(world), 9).find('('), std::string::npos) << "with values";
  }
}

// A timeless module printed with its age keeps no birth of its own in a word without ids
// (it joins the run beside it): its text makes the ids again, and reads right.
TEST(WordsWithoutIds, ATimelessModuleWithAnAgeIsWrittenFromTheReplayedWord) {
  auto program = testing_support::compileOrFail(R"(lsystem timeless {
  axiom (F, 0) (I, 0.5)
  (F, 1) -> F I F
})");
  ASSERT_NE(program, nullptr);
  ASSERT_TRUE(ParallelRewrite(*program, program->systems[program->root]).rewritesByTable());
  World reference = growing(program, 1, false);
  World world = growing(program, 1, true);
  reference.advanceTo(16, 1.0);
  world.advanceTo(16, 1.0);
  ASSERT_GT(world.rootPool().size(), ParallelRewrite::kMinimumCells);
  ASSERT_FALSE(world.rootPool().holdsIds());
  EXPECT_EQ(ran(reference), "compact-serial 14, table-alone 2");
  EXPECT_EQ(ran(world), "table-alone 16");
  const std::string expected = formatWord(captureWord(reference), 9);
  EXPECT_NE(expected.find("(I, 16.5)"), std::string::npos) << "the axiom's I, kept";
  EXPECT_EQ(wordText(world, false), expected);
  EXPECT_TRUE(world.rootPool().holdsIds()) << "read with its ids";
}

// The replay of the ids is held to the memory limit as the development's words are: a
// word it would write is counted at the development's bound a module (25 bytes here),
// besides the word without ids, the anchor and the word it rewrites. Koch at n = 8
// (781,249 modules) grows without ids under a limit of 19.5 MiB, whose development counts
// the new word at 18.6 MiB beside 0.2 MiB, and its replay (18.6 MiB beside 0.9 MiB held,
// and the word at n = 7 with its ids) does not fit: the first reader gets a LimitError,
// and the word is left as it was, so that the next reader gets it again. Under 24 MiB it
// fits, and the reader sees the ids of the world grown with them.
TEST(WordsWithoutIds, AReplayPastTheMemoryLimitStopsWithALimitError) {
  auto program = testing_support::compileOrFail(kKoch);
  ASSERT_NE(program, nullptr);
  World withIds = growing(program, 1, false);
  withIds.advanceTo(8, 1.0);
  for (const double mebibytes : {19.5, 24.0}) {
    WorldDef def;
    def.limits.maxMemoryBytes = static_cast<uint64_t>(mebibytes * 1024 * 1024);
    World world(program, def);
    world.advanceTo(8, 1.0);
    const Pool& pool = world.rootPool();
    ASSERT_EQ(pool.size(), 781'249u);
    ASSERT_FALSE(pool.holdsIds());
    if (mebibytes == 24.0) {
      expectSameCells(withIds.rootPool(), pool, "replayed under 24 MiB");
      continue;
    }
    for (int reader = 0; reader < 2; ++reader) {
      try {
        (void)pool.cellAt(0);
        ADD_FAILURE() << "no limit, reader " << reader;
      } catch (const LimitError& error) {
        const std::string message = error.what();
        EXPECT_NE(message.find("giving the word of 781249 modules its ids again"), std::string::npos) << message;
        EXPECT_NE(message.find("--max-memory"), std::string::npos) << message;
      }
      EXPECT_FALSE(pool.holdsIds());
      EXPECT_EQ(pool.compactWord().size(), 781'249u);
    }
  }
}

}  // namespace
}  // namespace ontogen
