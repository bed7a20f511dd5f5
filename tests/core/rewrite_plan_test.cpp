// The planner of linear rewrites (core/rewrite_plan.h): every strategy, forced where it
// applies, writes the serial pass's word bit for bit on 1, 2, 3 and 7 threads, and the
// world's statistics say that it ran; the unforced plan picks by the facts.

#include <gtest/gtest.h>

#include <bit>
#include <string>
#include <vector>

#include "core/rewrite_plan.h"
#include "core/world.h"
#include "test_support.h"

namespace ontogen {
namespace {

using S = RewriteStrategy;

struct Grown {
  std::unique_ptr<World> world;
  WorldStats stats;
};

Grown grow(const std::shared_ptr<const Program>& program, double until, unsigned threads,
           std::optional<RewriteStrategy> strategy) {
  WorldDef def;
  def.seed = 11;
  def.threads = threads;
  def.testRewriteStrategy = strategy;
  Grown grown{std::make_unique<World>(program, def), {}};
  grown.world->advanceTo(until, 1.0);
  grown.stats = grown.world->stats();
  return grown;
}

uint64_t ran(const Grown& grown, RewriteStrategy strategy) {
  return grown.stats.rewrites[static_cast<size_t>(strategy)];
}

void expectSameWords(const World& serial, const World& other, const std::string& what) {
  const Pool& a = serial.rootPool();
  const Pool& b = other.rootPool();
  ASSERT_EQ(a.size(), b.size()) << what;
  ASSERT_EQ(a.stateArena().size(), b.stateArena().size()) << what;
  for (CellCursor x = a.cursor(), y = b.cursor(); !x.done(); x.next(), y.next())
    ASSERT_TRUE(x.master() == y.master() && x.stateOffset() == y.stateOffset() && x.id() == y.id() &&
                std::bit_cast<uint64_t>(x.birth()) == std::bit_cast<uint64_t>(y.birth()))
        << what << ": cell " << x.index();
  for (size_t k = 0; k < a.stateArena().size(); ++k)
    ASSERT_EQ(std::bit_cast<uint64_t>(a.stateArena()[k]), std::bit_cast<uint64_t>(b.stateArena()[k]))
        << what << ": state value " << k;
}

struct Model {
  std::string name, text;
  double until;
  std::vector<RewriteStrategy> strategies;  // those that apply to it
};

std::vector<Model> models() {
  std::string signals;
  for (int i = 0; i < 600; ++i) signals += " b a a a a a a";
  return {
      // Records without context: every kind of successor, draws and me.parent.
      {"records without context",
       "cell A(x = 1) { lifetime 1; rules { terminal: x += 1, -> A(x * 0.5) B(uniform(0, 1)) me; } }\n"
       "cell B(y = 0) { lifetime 1; rules { terminal: -> =B(y + me.parent) C; } }\n"
       "cell C { lifetime 2; }\ncell D(z = 0) { lifetime 1; rules { terminal: z += 1; } }\n"
       "system s { pool linear; axiom D A; }\n",
       9,
       {S::Serial}},
      // Records with context, conditions and chances, rewritten instant by instant.
      {"records with context",
       "lsystem g {\n  axiom A(1) B(1)\n  A(x) -> A(x * 0.5) B(x)\n"
       "  A(x) < B(y) : y > 0.3 -> B(x + y) A(y) : 0.6\n  A(x) < B(y) -> B(y + uniform(0, 1)) : 0.4\n"
       "  B(y) > A(z) -> B(y - z)\n  B(y) -> B(y) A(y * 2)\n}\n",
       14,
       {S::Serial}},
      // A compact word of labels walked by its table (words without ids where it may).
      {"Koch",
       "lsystem koch {\n  axiom F\n  F -> F + F - F - F + F\n}\n",
       5,
       {S::Serial, S::CompactSerial, S::TableAlone, S::TableBounds, S::CompactSlices}},
      // A compact word with values, each successor's one operation on its cell's.
      {"parametric",
       testing_support::kParametric,
       12,
       {S::Serial, S::CompactSerial, S::TableAlone, S::TableBounds, S::CompactSlices}},
      // A compact word whose choices vary with the context and by chance, one for one.
      {"signals by chance",
       "lsystem d {\n  axiom" + signals + "\n  b < a -> b : 0.9\n  b < a -> c : 0.1\n  b -> a\n  c -> a\n}\n",
       12,
       {S::Serial, S::CompactSerial, S::OneForOne, S::Parts, S::CompactSlices}},
  };
}

TEST(RewritePlan, EveryStrategyWritesTheSerialWordOnEveryThreadCountAndSaysItRan) {
  for (const Model& model : models()) {
    SCOPED_TRACE(model.name);
    auto program = testing_support::compileOrFail(model.text);
    ASSERT_NE(program, nullptr);
    const Grown serial = grow(program, model.until, 1, S::Serial);
    ASSERT_GT(ran(serial, S::Serial), 0u);
    for (size_t k = 0; k < kRewriteStrategyCount; ++k) {
      if (k == static_cast<size_t>(S::Serial)) continue;
      EXPECT_EQ(serial.stats.rewrites[k], 0u) << k;
    }
    for (RewriteStrategy strategy : model.strategies) {
      for (unsigned threads : {1u, 2u, 3u, 7u}) {
        const std::string what =
            std::string(rewriteStrategyName(strategy)) + " on " + std::to_string(threads) + " threads";
        const Grown grown = grow(program, model.until, threads, strategy);
        EXPECT_GT(ran(grown, strategy), 0u) << what;
        expectSameWords(*serial.world, *grown.world, what);
        EXPECT_EQ(grown.stats.events, serial.stats.events) << what;
        EXPECT_EQ(grown.stats.cellsBorn, serial.stats.cellsBorn) << what;
      }
    }
  }
}

// A strategy forced where it does not apply leaves the plan as it was: Koch's fixed
// choices are not one for one, and a word with lineage logged keeps its records.
TEST(RewritePlan, AStrategyForcedWhereItDoesNotApplyIsNotTaken) {
  auto koch = testing_support::compileOrFail("lsystem koch {\n  axiom F\n  F -> F + F - F - F + F\n}\n");
  ASSERT_NE(koch, nullptr);
  const Grown grown = grow(koch, 5, 2, S::OneForOne);
  EXPECT_EQ(ran(grown, S::OneForOne), 0u);
  EXPECT_EQ(ran(grown, S::Parts), 0u);
  EXPECT_EQ(ran(grown, S::TableAlone), 5u);  // a small word written without ids: the table alone
  WorldDef def;
  def.recordLineage = true;
  def.testRewriteStrategy = S::TableBounds;
  World world(koch, def);
  world.advanceTo(5, 1.0);
  EXPECT_EQ(world.stats().rewrites[static_cast<size_t>(S::Serial)], 5u);
  EXPECT_EQ(world.stats().rewrites[static_cast<size_t>(S::TableBounds)], 0u);
}

TEST(RewritePlan, CountsArePrintedByTheStrategiesNames) {
  RewriteCounts counts{};
  EXPECT_EQ(formatRewriteCounts(counts), "");
  counts[static_cast<size_t>(S::TableAlone)] = 5;
  counts[static_cast<size_t>(S::CompactSlices)] = 2;
  counts[static_cast<size_t>(S::Serial)] = 1;
  EXPECT_EQ(formatRewriteCounts(counts), "serial 1, table-alone 5, compact-slices 2");
  for (size_t k = 0; k < kRewriteStrategyCount; ++k)
    for (size_t j = 0; j < k; ++j)
      EXPECT_NE(rewriteStrategyName(static_cast<S>(k)), rewriteStrategyName(static_cast<S>(j)));
}

RewriteFacts compactFacts(size_t size, unsigned threads) {
  RewriteFacts facts;
  facts.pass = RewritePass::Compact;
  facts.size = size;
  facts.threads = threads;
  facts.shape.compact = true;
  return facts;
}

// The unforced plan and the thread count it gives, decided once.
TEST(RewritePlan, TheUnforcedPlanFollowsTheFacts) {
  const size_t large = kMinimumSliceCells, small = kMinimumSliceCells - 1;
  RewriteFacts koch = compactFacts(large, 4);
  koch.shape.byTable = true;
  EXPECT_EQ(planRewrite(koch).strategy, S::TableBounds);
  EXPECT_EQ(planRewrite(koch).threads, 4u);
  koch.boundsMissed = true;
  EXPECT_EQ(planRewrite(koch).strategy, S::CompactSlices);
  koch.threads = 1;
  EXPECT_EQ(planRewrite(koch).strategy, S::TableAlone);
  koch.size = small;
  koch.threads = 4;
  EXPECT_EQ(planRewrite(koch).strategy, S::CompactSerial);  // small: one thread
  EXPECT_EQ(planRewrite(koch).threads, 1u);
  koch.withoutIds = true;
  EXPECT_EQ(planRewrite(koch).strategy, S::TableAlone);

  RewriteFacts signal = compactFacts(large, 2);
  signal.shape.choiceVaries = signal.shape.oneForOne = true;
  EXPECT_EQ(planRewrite(signal).strategy, S::OneForOne);
  signal.inPlaceRefused = true;
  EXPECT_EQ(planRewrite(signal).strategy, S::CompactSlices);  // the growth not known yet
  signal.growthKnown = true;
  EXPECT_EQ(planRewrite(signal).strategy, S::Parts);
  signal.threads = 1;
  EXPECT_EQ(planRewrite(signal).strategy, S::CompactSerial);

  // A word of records has one pass, on one thread, whatever is forced or the size.
  RewriteFacts records;
  records.pass = RewritePass::Records;
  records.size = large;
  records.threads = 3;
  EXPECT_EQ(planRewrite(records).strategy, S::Serial);
  EXPECT_EQ(planRewrite(records).threads, 1u);
  records.forced = S::CompactSlices;
  EXPECT_EQ(planRewrite(records).strategy, S::Serial);
  EXPECT_EQ(planRewrite(records).threads, 1u);
}

// The threads are decided once, by the strategy, forced or chosen: a strategy of one pass
// on one thread takes one whatever the world has; the others take every thread the world
// has, at any size once forced (a word of ten modules here).
TEST(RewritePlan, AStrategyOfOneThreadTakesOneAndTheOthersTakeTheWorlds) {
  for (unsigned threads : {1u, 2u, 7u}) {
    for (size_t k = 0; k < kRewriteStrategyCount; ++k) {
      const S strategy = static_cast<S>(k);
      RewriteFacts facts = compactFacts(10, threads);
      if (!rewritesCompactWords(strategy)) facts.pass = RewritePass::Records;
      facts.shape.byTable = facts.shape.choiceVaries = facts.shape.oneForOne = true;
      facts.growthKnown = true;
      facts.forced = strategy;
      ASSERT_TRUE(rewriteApplies(strategy, facts)) << rewriteStrategyName(strategy);
      const RewritePlan plan = planRewrite(facts);
      EXPECT_EQ(plan.strategy, strategy);
      const bool oneThread = strategy == S::Serial || strategy == S::CompactSerial || strategy == S::TableAlone;
      EXPECT_EQ(plan.threads, oneThread ? 1u : threads) << rewriteStrategyName(strategy) << " on " << threads;
    }
  }
}

}  // namespace
}  // namespace ontogen
