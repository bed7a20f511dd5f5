// The engine's semantics: reproducibility, step-size independence, limits, ids.

#include <gtest/gtest.h>

#include <set>

#include "core/word.h"
#include "interpreters/text/word_text.h"
#include "core/world.h"
#include "test_support.h"

namespace ontogen {
namespace {

using testing_support::compileOrFail;

const char* kStochasticTimed = R"(
lsystem plant {
  axiom (A(1), 0)
  (A(x), 1.3) -> (A(x + 1), uniform(0, 0.5)) [ (B(x * gaussian(1, 0.1)), 0) ] : 0.6
  (A(x), 1.3) -> (A(x + 2), 0.1) : 0.4
  (B(y), 0.7) -> (B(y), uniform(0, 0.3)) C
}
)";

std::vector<WordCell> develop(const std::shared_ptr<const Program>& program, uint64_t seed, double until, double step) {
  World world(program, WorldDef{.seed = seed});
  world.advanceTo(until, step);
  return captureWord(world);
}

void expectSameWord(const std::vector<WordCell>& a, const std::vector<WordCell>& b, double ageTolerance) {
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].label, b[i].label);
    EXPECT_EQ(a[i].id, b[i].id);
    EXPECT_EQ(a[i].params, b[i].params) << i;
    EXPECT_NEAR(a[i].age, b[i].age, ageTolerance) << i;
  }
}

TEST(World, SameSeedSameWord) {
  auto program = compileOrFail(kStochasticTimed);
  auto a = develop(program, 42, 9.0, 0.1);
  auto b = develop(program, 42, 9.0, 0.1);
  expectSameWord(a, b, 0);
  EXPECT_GT(a.size(), 20u);
}

TEST(World, DifferentSeedsDiffer) {
  auto program = compileOrFail(kStochasticTimed);
  EXPECT_NE(formatWord(develop(program, 1, 9.0, 0.1)), formatWord(develop(program, 2, 9.0, 0.1)));
}

TEST(World, StochasticTimedWordDoesNotDependOnTheStep) {
  // Random streams are keyed by the seed, the cell's lineage id and the event's exact
  // time, never by the order of processing.
  auto program = compileOrFail(kStochasticTimed);
  auto fine = develop(program, 7, 9.0, 0.01);
  for (double step : {0.1, 0.5, 1.0, 9.0}) {
    SCOPED_TRACE("step " + std::to_string(step));
    expectSameWord(fine, develop(program, 7, 9.0, step), 1e-9);
  }
}

TEST(World, WordAtAnIntermediateTimeWhateverTheRoute) {
  auto program = compileOrFail(kStochasticTimed);
  World direct(program, WorldDef{.seed = 3});
  direct.advanceTo(6.5, 6.5);
  World stepped(program, WorldDef{.seed = 3});
  for (double t : {1.0, 2.6, 2.61, 5.2, 6.5}) stepped.advanceTo(t, 0.3);
  expectSameWord(captureWord(direct), captureWord(stepped), 1e-9);
}

TEST(World, CopiesDevelopIndependently) {
  auto program = compileOrFail(kStochasticTimed);
  World original(program, WorldDef{.seed = 5});
  original.advanceTo(3, 0.5);
  World copy(original);
  copy.advanceTo(8, 0.5);
  original.advanceTo(8, 0.5);
  expectSameWord(captureWord(original), captureWord(copy), 0);
}

// Many worlds side by side from one compiled program, moved about in a vector as it
// grows: each develops as a world made alone would, nested systems included (their
// reads of parent.x go through the moved world).
TEST(World, ManyWorldsFromOneProgramAreMovableAndIndependent) {
  for (const char* model : {"orchard.cell", "markov_melody.cell"}) {
    auto program = testing_support::compileModel(model);
    std::vector<World> worlds;
    for (uint64_t seed = 1; seed <= 40; ++seed) worlds.emplace_back(program, WorldDef{.seed = seed});
    for (World& world : worlds) world.advanceTo(6, 0.5);
    std::vector<World> moved;
    for (World& world : worlds) moved.push_back(std::move(world));
    for (uint64_t seed : {1u, 17u, 40u}) {
      World alone(program, WorldDef{.seed = seed});
      alone.advanceTo(6, 0.5);
      const World& many = moved[seed - 1];
      EXPECT_EQ(formatWord(captureWord(many)), formatWord(captureWord(alone))) << model << " seed " << seed;
    }
    moved[3].advanceTo(8, 0.5);  // a moved world develops on
    World alone(program, WorldDef{.seed = 4});
    alone.advanceTo(8, 0.5);
    EXPECT_EQ(formatWord(captureWord(moved[3])), formatWord(captureWord(alone))) << model;
  }
}

TEST(World, CellLimitStopsGrowthWithAMessage) {
  auto program = compileOrFail("lsystem a { axiom A\n A -> A A\n }");
  WorldDef def;
  def.limits.maxCells = 1000;
  World world(program, def);
  try {
    world.advanceTo(20, 1);
    FAIL() << "the limit was not enforced";
  } catch (const LimitError& error) {
    EXPECT_NE(std::string(error.what()).find("1000 cells"), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find("--max-cells"), std::string::npos) << error.what();
  }
}

TEST(World, MemoryLimitStopsGrowthWithAMessage) {
  auto program = compileOrFail("lsystem a { axiom A(1)\n A(x) -> A(x) A(x + 1)\n }");
  WorldDef def;
  def.limits.maxMemoryBytes = 4 << 20;
  World world(program, def);
  EXPECT_THROW(world.advanceTo(30, 1), LimitError);
}

// A word that grew tenfold once and then stays the same size must not trip the memory
// limit through the room reserved for a growth that does not come.
TEST(World, MemoryLimitCountsCellsWrittenNotRoomReserved) {
  auto program = compileOrFail(
      "lsystem a { axiom S\n S -> T T T T T T T T T T\n T -> U U U U U U U U U U\n"
      " U -> V V V V V V V V V V\n V -> V\n }");
  WorldDef def;
  def.limits.maxMemoryBytes = 100'000;  // 1000 cells of 24 bytes, twice, fit; 10,500 reserved would not
  World world(program, def);
  EXPECT_NO_THROW(world.advanceTo(12, 1));
  EXPECT_EQ(world.rootPool().size(), 1000u);
}

TEST(World, RunawayRenewalHitsTheEventLimit) {
  auto program = compileOrFail("lsystem a { axiom (A, 0)\n (A, 1e-9) -> (A, 0)\n }");
  WorldDef def;
  def.limits.maxEventsPerStep = 10000;
  World world(program, def);
  try {
    world.advanceTo(1, 1);
    FAIL();
  } catch (const LimitError& error) {
    EXPECT_NE(std::string(error.what()).find("--max-events"), std::string::npos);
  }
}

TEST(World, IdsAreStableAndUnique) {
  auto program = compileOrFail("lsystem a { axiom A\n A -> A B\n B -> B\n }");
  World world(program);
  world.advanceTo(10, 1);
  auto word = captureWord(world);
  std::set<uint64_t> ids;
  for (const auto& cell : word) ids.insert(cell.id);
  EXPECT_EQ(ids.size(), word.size());
  // A module renewed by its own production keeps... a new id; `me` would keep it.
  auto keeper = compileOrFail("cell A(n = 0) { rules { n += 1, -> me; } }\nsystem s { pool linear; axiom A; }");
  World cells(keeper);
  uint64_t first = cells.rootPool().cells()[0].id;
  cells.advanceTo(5, 1);
  EXPECT_EQ(cells.rootPool().cells()[0].id, first);
}

TEST(World, EventsAtTheSameInstantHappenTogether) {
  // Both A's die at t = 1; the right one reads its left neighbour as it was just before.
  auto program = compileOrFail("lsystem a { axiom A(1) A(2)\n A(l) < A(x) -> A(l + x)\n A(x) -> B(x)\n }");
  World world(program);
  world.advanceTo(1, 0.3);
  EXPECT_EQ(formatWord(captureWord(world)), "B(1) A(3)");
}

}  // namespace
}  // namespace ontogen

namespace ontogen {
namespace {

TEST(World, SymbolsThatAreNoPredecessorKeepAgeing) {
  auto program = testing_support::compileOrFail("lsystem keep { axiom A +\n A -> A F\n }");
  World world(program);
  world.advanceTo(2.5, 1);
  auto word = captureWord(world);
  ASSERT_EQ(formatWord(word), "A F F +");
  EXPECT_NEAR(word[0].age, 0.5, 1e-12);  // renewed at t = 2
  EXPECT_NEAR(word[1].age, 0.5, 1e-12);  // born at t = 2
  EXPECT_NEAR(word[2].age, 1.5, 1e-12);  // born at t = 1
  EXPECT_NEAR(word[3].age, 2.5, 1e-12);  // never dies
}

// A stochastic production whose context alternatives both match takes part in the
// choice once: against another production of the same weight it wins about half the time
// (counted once per matching alternative it would win two thirds).
TEST(World, ContextAlternativesCountOnceInAStochasticChoice) {
  std::string axiom;
  for (int i = 0; i < 2000; ++i) axiom += " X A";
  auto program = compileOrFail("lsystem choice {\n  axiom" + axiom + "\n  X > (A | *) -> P : 1\n  X > * -> Q : 1\n}\n");
  ASSERT_NE(program, nullptr);
  World world(program, WorldDef{.seed = 7});
  world.advanceTo(1, 1);
  int p = 0, q = 0;
  for (const WordCell& cell : captureWord(world)) {
    p += cell.label == "P";
    q += cell.label == "Q";
  }
  EXPECT_EQ(p + q, 2000);
  EXPECT_NEAR(p / 2000.0, 0.5, 0.05);
}

}  // namespace
}  // namespace ontogen
