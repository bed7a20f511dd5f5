// The rewriting by slices (core/parallel_rewrite.h) writes the word the one-pass serial
// rewriting writes, bit for bit: records, ids, birth times, state values and statistics,
// on any number of threads; and the world's statistics name the strategies the planner
// took (core/rewrite_plan.h) on each thread count.

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <string>
#include <vector>

#include "core/parallel_rewrite.h"
#include "core/world.h"
#include "test_support.h"

namespace ontogen {
namespace {

// Every kind of successor the pass writes: `me`, `=X`, stateful and stateless cells,
// arguments that draw and that read me.parent, a calculation without an action (a
// renewal), and a cell with no rules that renews itself every 2 s.
const char* kEveryKindOfSuccessor = R"(
cell A(x = 1) { lifetime 1; rules { terminal: x += 1, -> A(x * 0.5) B(uniform(0, 1)) me; } }
cell B(y = 0) { lifetime 1; rules { terminal: -> =B(y + me.parent) C; } }
cell C { lifetime 2; }
cell D(z = 0) { lifetime 1; rules { terminal: z += 1; } }
system s { pool linear; axiom D A; }
)";

const char* kKoch = R"(lsystem koch {
  axiom F
  F -> F + F - F - F + F
})";

struct Grown {
  std::unique_ptr<World> world;
  WorldStats stats;
};

// `slices` false: the one-pass serial rewriting, the reference.
Grown grow(const std::shared_ptr<const Program>& program, double until, unsigned threads, bool slices = true) {
  WorldDef def;
  def.seed = 11;
  def.threads = threads;
  def.rewriteBySlices = slices;
  Grown grown{std::make_unique<World>(program, def), {}};
  grown.world->advanceTo(until, 1.0);
  grown.stats = grown.world->stats();
  return grown;
}

void expectSameWords(const World& serial, const World& parallel, const std::string& what) {
  const Pool& a = serial.rootPool();
  const Pool& b = parallel.rootPool();
  ASSERT_EQ(a.size(), b.size()) << what;
  ASSERT_EQ(a.stateArena().size(), b.stateArena().size()) << what;
  // Through cursors: a label-only word may be kept compact (docs/COMPACT_WORDS.md).
  for (CellCursor x = a.cursor(), y = b.cursor(); !x.done(); x.next(), y.next()) {
    ASSERT_TRUE(x.master() == y.master() && x.stateOffset() == y.stateOffset() && x.id() == y.id() &&
                std::bit_cast<uint64_t>(x.birth()) == std::bit_cast<uint64_t>(y.birth()))
        << what << ": cell " << x.index();
  }
  for (size_t k = 0; k < a.stateArena().size(); ++k)
    ASSERT_EQ(std::bit_cast<uint64_t>(a.stateArena()[k]), std::bit_cast<uint64_t>(b.stateArena()[k]))
        << what << ": state value " << k;
  // Cells found by index, as interpretation and queries find them: a compact word finds
  // their values through its block index.
  for (size_t i = 0; i < a.size(); i += 61) {
    ASSERT_EQ(a.stateOffset(i), b.stateOffset(i)) << what << ": cell " << i;
    ASSERT_EQ(a.cellAt(i).id, b.cellAt(i).id) << what << ": cell " << i;
  }
}

// The strategies that rewrote the word and how often (core/rewrite_plan.h), as --stats
// prints them: "table-alone 5, table-bounds 3".
std::string ran(const WorldStats& stats) {
  return formatRewriteCounts(stats.rewrites);
}
std::string ran(const Grown& grown) {
  return ran(grown.stats);
}
bool compact(const Grown& grown) {
  return grown.world->rootPool().holdsCompactWord();
}

// A thread count and the strategies expected to rewrite the word on it.
struct Route {
  unsigned threads;
  std::string strategies;
};

// Grows `program` to `until` on each route's thread count and expects `serial`'s word,
// events and births, rewritten by the route's strategies.
void expectTheSerialWordOnEveryThreadCount(const std::shared_ptr<const Program>& program, double until,
                                           const Grown& serial, const std::vector<Route>& routes) {
  for (const Route& route : routes) {
    const Grown grown = grow(program, until, route.threads);
    EXPECT_EQ(ran(grown), route.strategies) << route.threads << " threads";
    expectSameWords(*serial.world, *grown.world, std::to_string(route.threads) + " threads");
    EXPECT_EQ(grown.stats.events, serial.stats.events);
    EXPECT_EQ(grown.stats.cellsBorn, serial.stats.cellsBorn);
  }
}

TEST(ParallelRewrite, EveryKindOfSuccessorIsWrittenAsTheSerialPassWritesIt) {
  auto program = testing_support::compileOrFail(kEveryKindOfSuccessor);
  ASSERT_NE(program, nullptr);
  const Grown serial = grow(program, 16, 1, false);
  ASSERT_GT(serial.world->rootPool().size(), 4 * ParallelRewrite::kMinimumCells);
  EXPECT_EQ(ran(serial), "serial 16");
  // A word whose rules draw and calculate keeps its records: the serial pass on any thread count.
  expectTheSerialWordOnEveryThreadCount(program, 16, serial,
                                        {{1, "serial 16"}, {2, "serial 16"}, {3, "serial 16"}, {7, "serial 16"}});
}

// Masters whose one rule has no choice or calculation and whose successors' arguments are
// straight-line code: the compact word evaluates those arguments for many cells at once
// (ParallelRewrite::flushBatch). Here with `me`, `=X`, two values a module, arguments
// reading age, time and id, a built-in function, a stateless successor, and a master with
// state and no rule, interleaved so that the batches of three masters fill and flush at
// different cells.
const char* kEvaluatedInBatches = R"(
cell A(x = 1, w = 2) { lifetime 1; rules { terminal: -> A(x * 0.5 + sqrt(w), w + age) B(x - id % 3, time) me C; } }
cell B(y = 0, z = 0) { lifetime 1; rules { terminal: -> =B(y + 0.5, z * 0.25 + id % 7) C G(y); } }
cell G(g = 0) { lifetime 3; rules { terminal: -> G(g + 1 / (1 + age)); } }
cell C { lifetime 2; }
cell E(v = 3) { lifetime 1; }
system s { pool linear; axiom E A B E; }
)";

TEST(ParallelRewrite, ArgumentsEvaluatedInBatchesEqualTheSerialPass) {
  auto program = testing_support::compileOrFail(kEvaluatedInBatches);
  ASSERT_NE(program, nullptr);
  const Grown serial = grow(program, 15, 1, false);
  ASSERT_GT(serial.world->rootPool().size(), 4 * ParallelRewrite::kMinimumCells);
  EXPECT_EQ(ran(serial), "serial 15");
  expectTheSerialWordOnEveryThreadCount(
      program, 15, serial,
      {{1, "compact-serial 15"},
       {2, "compact-serial 13, compact-slices 2"},
       {3, "compact-serial 13, compact-slices 2"},
       {7, "compact-serial 13, compact-slices 2"}});
}

// Words with state kept compact (ParallelRewrite::appliesToCompactWords): masters whose
// successors' values are evaluated in batches, with all-new successors in one run (A,
// with a stateless C in it, and fourteen successors crossing blocks of 64), `=X` (B),
// `me` (G), a renewal with state (E, whose lifetime of 1.5 makes two instants a step), a
// draw among constant chances (H), and arguments reading age, time, id, a built-in
// function and an enclosing system's state (parent.k).
const char* kStateKeptCompact = R"(
cell A(x = 1, w = 2) { lifetime 1;
  rules { terminal: -> A(x * 0.5 + sqrt(w), w + age) B(x - id % 5, time) C G(w)
                       G(1) G(2) G(3) G(4) G(5) G(6) G(7) G(8) G(9) A(parent.k, x); } }
cell B(y = 0, z = 0) { lifetime 1; rules { terminal: -> =B(y + 1, z * 0.25 + id % 7) C H(y); } }
cell G(g = 0) { lifetime 3; rules { terminal: -> G(g + 1 / (1 + age)) me; } }
cell H(h = 1) { lifetime 1;
  rules { terminal: -> H(h + 1) H(h * 2) : 0.3; terminal: -> H(h - 1) : 0.6; terminal: -> : 0.1; } }
cell C { lifetime 2; }
cell E(v = 3) { lifetime 1.5; }
system inner(k = 4) { pool linear; axiom E A B E H; }
system s { pool linear; axiom inner; }
)";

TEST(ParallelRewrite, AWordWithStateIsKeptCompactAsTheSerialPassWritesIt) {
  auto program = testing_support::compileOrFail(kStateKeptCompact);
  ASSERT_NE(program, nullptr);
  const auto inner = std::find_if(program->systems.begin(), program->systems.end(),
                                  [](const SystemDefinition& system) { return system.name == "inner"; });
  ASSERT_NE(inner, program->systems.end());
  ASSERT_TRUE(ParallelRewrite(*program, *inner).appliesToCompactWords());
  auto innerWorld = [](const Grown& grown) -> const World& {
    const World* world = grown.world->childOf(grown.world->rootPool().cellAt(0).id);
    if (!world) throw std::logic_error("no inner world");
    return *world;
  };
  const Grown serial = grow(program, 13, 1, false);
  ASSERT_GT(innerWorld(serial).rootPool().size(), 4 * ParallelRewrite::kMinimumCells);
  for (unsigned threads : {1u, 2u, 3u}) {
    const Grown grown = grow(program, 13, threads);
    EXPECT_TRUE(innerWorld(grown).rootPool().holdsCompactWord()) << threads << " threads";
    expectSameWords(innerWorld(serial), innerWorld(grown), std::to_string(threads) + " threads");
    EXPECT_EQ(innerWorld(grown).stats().events, innerWorld(serial).stats().events);
    EXPECT_EQ(innerWorld(grown).stats().cellsBorn, innerWorld(serial).stats().cellsBorn);
    EXPECT_EQ(ran(innerWorld(grown).stats()),
              threads == 1 ? "compact-serial 17" : "compact-serial 15, compact-slices 2")
        << threads << " threads";
  }
  // A master that reads its place (me.x) or its parent keeps the records.
  for (const char* reads : {"me.x", "me.parent"}) {
    auto model = testing_support::compileOrFail(std::string("lsystem p {\n  axiom A(1)\n  A(x) -> A(x + ") + reads +
                                                ") A(x)\n}\n");
    ASSERT_NE(model, nullptr);
    EXPECT_FALSE(ParallelRewrite(*model, model->systems[model->root]).appliesToCompactWords()) << reads;
  }
}

// A plant's bracketed word whose rules have no context (ABOP Fig. 1.24d): brackets are
// labels like any other, so the word is kept compact, and it reads as the serial pass of
// records writes it. With a context, brackets change what a neighbour is: records.
TEST(ParallelRewrite, ABracketedWordWithoutContextIsKeptCompactAsTheSerialPassWritesIt) {
  auto program =
      testing_support::compileOrFail("lsystem plant {\n  axiom X\n  X -> F [ + X ] F [ - X ] + X\n  F -> F F\n}\n");
  ASSERT_NE(program, nullptr);
  EXPECT_TRUE(ParallelRewrite(*program, program->systems[program->root]).appliesToCompactWords());
  const Grown serial = grow(program, 9, 1, false);
  ASSERT_FALSE(serial.world->rootPool().holdsCompactWord());
  ASSERT_GT(serial.world->rootPool().size(), 2 * ParallelRewrite::kMinimumCells);
  expectTheSerialWordOnEveryThreadCount(
      program, 9, serial,
      {{1, "table-alone 9"}, {2, "table-alone 8, table-bounds 1"}, {3, "table-alone 8, table-bounds 1"}});
  auto withContext = testing_support::compileOrFail("lsystem c {\n  axiom F [ F ] F\n  F < F -> F F\n}\n");
  ASSERT_NE(withContext, nullptr);
  EXPECT_FALSE(ParallelRewrite(*withContext, withContext->systems[withContext->root]).appliesToCompactWords());
}

// Label-only rules with constant chances (ABOP Fig. 1.27's stochastic plant, and a plain
// word whose drawn rules have contexts): the compact pass draws from each cell's stream as
// the records' passes do, so the words are the same, cell for cell.
TEST(ParallelRewrite, ADrawAmongLabelOnlyRulesIsTheSerialPassesDraw) {
  struct Case {
    std::string text;
    double until;
    std::vector<Route> routes;
  };
  const std::vector<Case> programs{
      {"lsystem plant {\n  axiom F\n  F -> F [ + F ] F [ - F ] F : 0.33\n  F -> F [ + F ] F : 0.33\n"
       "  F -> F [ - F ] F : 0.34\n}\n",
       11,
       {{1, "compact-serial 11"}, {2, "compact-serial 8, parts 3"}, {3, "compact-serial 8, parts 3"}}},
      {"lsystem drawn {\n  axiom a b a b b a\n  a < b -> a b : 0.5\n  a < b -> b : 0.25\n  b > a -> a b a : 2\n"
       "  b -> b a : 0.2\n  a -> a b : 0.6\n  a -> a : 0.4\n  a -> b : 0\n}\n",
       14,
       {{1, "compact-serial 14"}, {2, "compact-serial 14"}, {3, "compact-serial 14"}}}};
  for (const auto& [text, until, routes] : programs) {
    SCOPED_TRACE(text);
    auto program = testing_support::compileOrFail(text);
    ASSERT_NE(program, nullptr);
    ASSERT_TRUE(ParallelRewrite(*program, program->systems[program->root]).appliesToCompactWords());
    const Grown serial = grow(program, until, 1, false);
    ASSERT_GT(serial.world->rootPool().size(), ParallelRewrite::kMinimumCells);
    expectTheSerialWordOnEveryThreadCount(program, until, serial, routes);
  }
}

// Context-free words whose masters choose as the serial pass of records chooses: draws
// among rules of constant chances (a stochastic tree with values, and a master whose rules
// have no chance after the first); conditions, and chances that are expressions, in the
// cell's frame (a draw in a condition among them).
TEST(ParallelRewrite, AChoiceInAContextFreeWordIsTheSerialPassesChoice) {
  // The first draws by constant chances alone and evaluates its arguments in batches, so
  // its word is kept compact; the second chooses in the cell's frame, so its word keeps
  // its records and the serial pass on every thread count.
  const std::vector<std::pair<std::string, std::vector<Route>>> programs{
      {"lsystem tree {\n  axiom A(1) B\n"
       "  A(s) -> F(s) [ + A(s * 0.8) ] [ - A(s * 0.8) ] : 0.6\n"
       "  A(s) -> F(s) A(s * 0.8) : 0.35\n  A(s) -> A(s) : 0\n  A(s) -> : 0.05\n"
       "  B -> B B : 0.5\n  B -> B\n  B -> F(2) : 0.5\n"
       "  F(x) -> F(x * 1.1)\n}\n",
       {{1, "compact-serial 22"},
        {2, "compact-serial 21, compact-slices 1"},
        {3, "compact-serial 21, compact-slices 1"}}},
      {"lsystem conditions {\n  axiom A(0) B(3)\n"
       "  A(t) : t < 3 -> A(t + 1) B(t)\n  A(t) : t >= 3 && uniform(0, 1) < 0.9 -> A(0) [ + A(1) ]\n"
       "  B(x) -> B(x + 1) : 0.3 + 0.1 * sin(x)\n  B(x) -> B(x) B(x * 0.5) : 0.7\n}\n",
       {{1, "serial 22"}, {2, "serial 22"}, {3, "serial 22"}}}};
  for (const auto& [text, routes] : programs) {
    SCOPED_TRACE(text);
    auto program = testing_support::compileOrFail(text);
    ASSERT_NE(program, nullptr);
    const Grown serial = grow(program, 22, 1, false);
    ASSERT_GT(serial.world->rootPool().size(), 2 * ParallelRewrite::kMinimumCells);
    expectTheSerialWordOnEveryThreadCount(program, 22, serial, routes);
  }
}

TEST(ParallelRewrite, KochOnTwoThreadsIsKochOnOne) {
  auto program = testing_support::compileOrFail(kKoch);
  ASSERT_NE(program, nullptr);
  const Grown serial = grow(program, 8, 1, false);
  EXPECT_EQ(serial.world->rootPool().size(), 2u * 390625u - 1u);  // 2 * 5^8 - 1
  for (const Route& route : std::vector<Route>{{1, "table-alone 8"}, {2, "table-alone 7, table-bounds 1"}}) {
    const unsigned threads = route.threads;
    const Grown sliced = grow(program, 8, threads);
    EXPECT_EQ(ran(sliced), route.strategies) << threads << " threads";
    expectSameWords(*serial.world, *sliced.world, "Koch on " + std::to_string(threads) + " threads");
  }
}

// The benchmarks' Thue-Morse (labels only) and parametric (a value per module) words at
// 2^16 modules: by slices, as the serial pass writes them, id for id.
TEST(ParallelRewrite, ThueMorseAndParametricWordsAreWrittenAsTheSerialPassWritesThem) {
  struct Model {
    const char* name;
    const char* text;
    std::vector<Route> routes;
  };
  // Both go by their table: walked alone on one thread; on more, the last step, 2^15
  // modules at t = 15, is the first large enough for slices placed by the table's bounds.
  const std::vector<Route> kByTable{
      {1, "table-alone 16"}, {2, "table-alone 15, table-bounds 1"}, {7, "table-alone 15, table-bounds 1"}};
  for (const Model& model : {Model{"Thue-Morse", testing_support::kThueMorse, kByTable},
                             Model{"parametric", testing_support::kParametric, kByTable}}) {
    auto program = testing_support::compileOrFail(model.text, model.name);
    ASSERT_NE(program, nullptr);
    const Grown serial = grow(program, 16, 1, false);
    ASSERT_EQ(serial.world->rootPool().size(), 65536u) << model.name;
    for (const Route& route : model.routes) {
      const unsigned threads = route.threads;
      const Grown sliced = grow(program, 16, threads);
      EXPECT_EQ(ran(sliced), route.strategies) << model.name << " on " << threads << " threads";
      expectSameWords(*serial.world, *sliced.world,
                      std::string(model.name) + " on " + std::to_string(threads) + " threads");
      EXPECT_EQ(sliced.stats.cellsBorn, serial.stats.cellsBorn) << model.name;
    }
  }
}

// A word rewritten by a table (pools/table_rewrite.h): labels whose lifetimes differ, so
// that some modules expire while their neighbours are kept; a label without rules that
// renews itself; eleven successors (more than one store of eight labels, and runs across
// bitmap words); an axiom of 70,000 modules, whose ids past k = 65,533 go to the table of
// wide k, kept and renewed.
std::string tableProgram() {
  std::string axiom;
  for (int i = 0; i < 70'000; ++i) axiom += i % 9000 == 4 ? "F G " : "H ";
  return "cell F { lifetime 1; rules { terminal: -> F G F; } }\n"
         "cell G { lifetime 3; rules { terminal: -> H F H H G H H F H H H; } }\n"
         "cell H { lifetime 2.5; }\n"
         "system s { pool linear; axiom " +
         axiom + "; }\n";
}

TEST(ParallelRewrite, AWordRewrittenByATableIsWrittenAsTheSerialPassWritesIt) {
  auto program = testing_support::compileOrFail(tableProgram());
  ASSERT_NE(program, nullptr);
  ASSERT_TRUE(ParallelRewrite(*program, program->systems[program->root]).rewritesByTable());
  const Grown serial = grow(program, 12, 1, false);
  ASSERT_GT(serial.world->rootPool().size(), 100'000u);
  expectTheSerialWordOnEveryThreadCount(program, 12, serial,
                                        {{1, "table-alone 20"}, {2, "compact-slices 20"}, {3, "compact-slices 20"}});
  // Koch and Thue-Morse go by the table; a successor that keeps the cell's id does not.
  for (const char* text : {kKoch, testing_support::kThueMorse}) {
    auto model = testing_support::compileOrFail(text);
    ASSERT_NE(model, nullptr);
    EXPECT_TRUE(ParallelRewrite(*model, model->systems[model->root]).rewritesByTable()) << text;
  }
  auto keeps = testing_support::compileOrFail("lsystem k {\n  axiom A\n  A -> A B\n  B -> =B A\n}\n");
  ASSERT_NE(keeps, nullptr);
  EXPECT_FALSE(ParallelRewrite(*keeps, keeps->systems[keeps->root]).rewritesByTable());
}

// A production of 65,581 successors, whose k run past the largest a run holds
// (CompactWord::kLargestRunK), applied by slices: 2 W make a word of 131,162 modules at
// t = 1, and both rewrite again at t = 2 and 3.
constexpr int kWideSuccessors = static_cast<int>(CompactWord::kLargestRunK) + 46;
std::string wideProgram() {
  std::string text = "lsystem wide {\n  axiom W W\n  W -> W";
  for (int i = 0; i < kWideSuccessors; ++i) text += " x";
  return text + "\n}\n";
}

TEST(ParallelRewrite, ARuleOfMoreSuccessorsThanARunHoldsIsWrittenAsTheSerialPassWritesIt) {
  auto program = testing_support::compileOrFail(wideProgram());
  ASSERT_NE(program, nullptr);
  const Grown serial = grow(program, 3, 1, false);
  ASSERT_EQ(serial.world->rootPool().size(), 2u * (1 + 3 * kWideSuccessors)) << "W, then the x of each step";
  for (const Route& route : std::vector<Route>{{1, "compact-serial 1, compact-slices 2"},
                                               {2, "compact-serial 1, compact-slices 2"},
                                               {3, "compact-serial 1, compact-slices 2"}}) {
    const unsigned threads = route.threads;
    const Grown sliced = grow(program, 3, threads);
    EXPECT_EQ(ran(sliced), route.strategies) << threads << " threads";
    expectSameWords(*serial.world, *sliced.world, "wide rule on " + std::to_string(threads) + " threads");
  }
}

// The context signal of the benchmarks: labels only, no frame.
std::string signalProgram(int cells) {
  std::string axiom = "b";
  for (int i = 1; i < cells; ++i) axiom += " a";
  return "lsystem signal {\n  axiom " + axiom + "\n  b < a -> b\n  b -> a\n}\n";
}

TEST(ParallelRewrite, ALabelOnlyContextIsWrittenAsTheSerialPassWritesIt) {
  auto program = testing_support::compileOrFail(signalProgram(50'000));
  ASSERT_NE(program, nullptr);
  const Grown serial = grow(program, 40, 1, false);
  EXPECT_EQ(ran(serial), "serial 40");
  // The signal has moved 40 places.
  EXPECT_EQ(program->masters[serial.world->rootPool().cellAt(40).master].label, "b");
  for (const Route& route : std::vector<Route>{{1, "one-for-one 40"}, {2, "one-for-one 40"}, {5, "one-for-one 40"}}) {
    const unsigned threads = route.threads;
    const Grown parallel = grow(program, 40, threads);
    EXPECT_EQ(ran(parallel), route.strategies) << threads << " threads";
    expectSameWords(*serial.world, *parallel.world, "signal on " + std::to_string(threads) + " threads");
    EXPECT_EQ(parallel.stats.events, serial.stats.events);
  }
}

// Where every rule that acts writes one successor, each thread writes its slice of the next
// word in place (ParallelRewrite::rewriteOneForOne), given a run a module, and the runs it
// wrote are moved together after it (CompactWord::closeRunGaps). Here in a word of many
// signals, each going on by chance or dying, whose events break the runs at random; and
// in the signal along the axiom's one run of 200,000 modules, where the slices of two and
// three threads start at places in the run past two bytes (CompactWord's wide k).
TEST(ParallelRewrite, AOneForOneWordIsWrittenInPlaceAsTheSerialPassWritesIt) {
  std::string signals;
  for (int i = 0; i < 6000; ++i) signals += " b a a a a a a";
  const std::vector<std::pair<std::string, std::string>> cases{
      {"signals by chance",
       "lsystem d {\n  axiom" + signals + "\n  b < a -> b : 0.9\n  b < a -> c : 0.1\n  b -> a\n  c -> a\n}\n"},
      {"one long run", signalProgram(200'000)}};
  for (const auto& [name, text] : cases) {
    SCOPED_TRACE(name);
    auto program = testing_support::compileOrFail(text);
    ASSERT_NE(program, nullptr);
    const Grown serial = grow(program, 12, 1, false);
    for (unsigned threads : {1u, 2u, 3u}) {
      const Grown parallel = grow(program, 12, threads);
      EXPECT_TRUE(compact(parallel)) << threads << " threads";
      EXPECT_EQ(ran(parallel), "one-for-one 12") << threads << " threads";
      expectSameWords(*serial.world, *parallel.world, name + " on " + std::to_string(threads) + " threads");
      EXPECT_EQ(parallel.stats.events, serial.stats.events);
      EXPECT_EQ(parallel.stats.cellsBorn, serial.stats.cellsBorn);
    }
  }
}

// Modules of one run that are kept, or renewed together, go out of the compact pass as
// one stretch (ParallelRewrite::rewriteRange): here runs of 150 modules, kept (P never
// expires) and renewed in stretches across blocks of 64, where A and B renew at deaths a
// trillionth apart, within one instant's tolerance, so that each keeps its own birth. A
// context that never matches (no Z is ever made) keeps the word from the table walk.
std::string stretchesProgram() {
  std::string successors;
  for (const auto& [label, count] : std::vector<std::pair<std::string, int>>{
           {"A", 40}, {"B", 30}, {"P", 70}, {"A", 5}, {"B", 1}, {"P", 1}, {"A", 1}, {"P", 2}})
    for (int i = 0; i < count; ++i) successors += " " + label;
  std::string axiom;
  for (int i = 0; i < 600; ++i) axiom += " S";
  return "cell S { lifetime 1; rules { terminal: ->" + successors +
         "; } }\ncell A { lifetime 1; rules { terminal: Z me: -> Z; } }\n"
         "cell B { lifetime 1.000000000001; rules { terminal: Z me: -> Z; } }\ncell P { }\ncell Z { }\n"
         "system s { pool linear; axiom" +
         axiom + "; }\n";
}

TEST(ParallelRewrite, ModulesKeptOrRenewedTogetherAreWrittenAsTheSerialPassWritesThem) {
  auto program = testing_support::compileOrFail(stretchesProgram());
  ASSERT_NE(program, nullptr);
  EXPECT_TRUE(ParallelRewrite(*program, program->systems[program->root]).appliesToCompactWords());
  const Grown serial = grow(program, 3.5, 1, false);
  ASSERT_FALSE(serial.world->rootPool().holdsCompactWord());
  ASSERT_GT(serial.world->rootPool().size(), 2 * ParallelRewrite::kMinimumCells);
  // A and B of one run were renewed at their own deaths: two births a trillionth apart.
  const CellView a = serial.world->rootPool().cellAt(0), b = serial.world->rootPool().cellAt(40);
  EXPECT_EQ(program->masters[a.master].label, "A");
  EXPECT_EQ(program->masters[b.master].label, "B");
  EXPECT_EQ(a.birth, 3.0);
  EXPECT_GT(b.birth, 3.0);
  EXPECT_LT(b.birth, 3.0 + 1e-9);
  expectTheSerialWordOnEveryThreadCount(
      program, 3.5, serial,
      {{1, "compact-serial 3"}, {2, "compact-serial 1, parts 2"}, {3, "compact-serial 1, parts 2"}});
}

// Labels only, with two modules of left context, right context, the wildcard and the
// word's ends: in a word of plain modules (matched by position) and in one with branches
// and an ignored module (matched through the bracket index).
std::string labelContextProgram(bool branches) {
  std::string axiom;
  for (int i = 0; i < 12'000; ++i)
    axiom += branches ? (i % 3 ? " a b c" : " a [ b c ] d") : (i % 3 ? " a b c" : " a b d");
  return "lsystem l {\n  axiom" + axiom + "\n" + (branches ? "  ignore: d\n" : "") +
         "  ∅ < a -> d\n  c > * ∅ -> a\n  b * < c -> d\n"
         "  a b < c -> a\n  c > a -> b\n  a < b > c -> c\n  d < a -> d\n  b -> a\n  d -> c\n}\n";
}

TEST(ParallelRewrite, LabelContextsInPlainAndBranchedWordsAreWrittenAsTheSerialPassWritesThem) {
  for (bool branches : {false, true}) {
    auto program = testing_support::compileOrFail(labelContextProgram(branches));
    ASSERT_NE(program, nullptr);
    const Grown serial = grow(program, 12, 1, false);
    ASSERT_GE(serial.world->rootPool().size(), ParallelRewrite::kMinimumCells);
    for (unsigned threads : {1u, 2u, 3u}) {
      const Grown parallel = grow(program, 12, threads);
      EXPECT_EQ(ran(parallel), branches ? "serial 12" : "one-for-one 12") << threads << " threads";
      expectSameWords(
          *serial.world, *parallel.world,
          std::string(branches ? "branched" : "plain") + " word on " + std::to_string(threads) + " threads");
    }
  }
}

// The pass on compact words (docs/COMPACT_WORDS.md, slice 5), which the linear pool does
// not store yet: from the engine's axiom, a compact word rewritten generation by
// generation reads as the engine's word, module for module (label, id, birth), on 1, 2
// and 3 threads, and counts the engine's events.
TEST(ParallelRewrite, LabelOnlyWordsRewrittenCompactReadAsTheEnginesWords) {
  struct Case {
    std::string name, text;
    int generations;
    size_t runs;  // at the end: an event's successors share a run; the axiom's ids are whole
  };
  const std::vector<Case> cases{{"Koch", kKoch, 6, 2 * 3125 - 1},
                                {"Thue-Morse", "lsystem t {\n  axiom a\n  a -> a b\n  b -> b a\n}\n", 12, 2048},
                                {"signal", signalProgram(3000), 30, 3000},
                                {"label contexts", labelContextProgram(false), 8, 36000}};
  for (const Case& model : cases) {
    SCOPED_TRACE(model.name);
    auto program = testing_support::compileOrFail(model.text);
    ASSERT_NE(program, nullptr);
    ParallelRewrite rewrite(*program, program->systems[program->root]);
    ASSERT_TRUE(rewrite.appliesToCompactWords());
    WorldDef def;
    def.seed = 11;
    std::vector<uint32_t> stateCounts;
    for (const MasterCell& master : program->masters) stateCounts.push_back(master.stateCount());
    for (unsigned threads : {1u, 2u, 3u}) {
      CompactWord word(stateCounts), next(stateCounts);
      World engine(program, def);
      for (CellCursor cell = engine.rootPool().cursor(); !cell.done(); cell.next())
        word.append(cell.master(), IdKey::whole(cell.id()), cell.birth(), nullptr);
      uint64_t compactEvents = 0;
      for (int generation = 1; generation <= model.generations; ++generation) {
        compactEvents += rewrite.rewriteCompact(word, generation, 0, threads, next).value().events;
        std::swap(word, next);
        engine.advanceTo(generation, 1.0);
        const Pool& pool = engine.rootPool();
        ASSERT_EQ(word.size(), pool.size()) << "generation " << generation;
        size_t i = 0;
        for (CompactWordCursor cell = word.cursor(); !cell.done(); cell.next(), ++i) {
          const CellView expected = pool.cellAt(i);
          ASSERT_TRUE(cell.master() == expected.master && cell.id() == expected.id &&
                      std::bit_cast<uint64_t>(cell.birth()) == std::bit_cast<uint64_t>(expected.birth))
              << "generation " << generation << ", cell " << i << ", " << threads << " threads";
        }
      }
      EXPECT_EQ(compactEvents, engine.stats().events) << threads << " threads";
      EXPECT_LE(word.runCount(), model.runs + 3 * threads) << "one more run a seam at most";
      EXPECT_GE(word.runCount(), model.runs);
    }
  }
}

// Context with bound values, conditions, chance and draws in the successors.
const char* kContextWithChoices = R"(lsystem g {
  axiom A(1) B(1)
  A(x) -> A(x * 0.5) B(x)
  A(x) < B(y) : y > 0.3 -> B(x + y) A(y) : 0.6
  A(x) < B(y) -> B(y + uniform(0, 1)) : 0.4
  B(y) > A(z) -> B(y - z)
  B(y) -> B(y) A(y * 2)
})";

TEST(ParallelRewrite, ContextWithChoicesIsWrittenAsTheSerialPassWritesIt) {
  auto program = testing_support::compileOrFail(kContextWithChoices);
  ASSERT_NE(program, nullptr);
  const Grown serial = grow(program, 25, 1, false);
  ASSERT_GT(serial.world->rootPool().size(), 4 * ParallelRewrite::kMinimumCells);
  for (unsigned threads : {1u, 2u, 3u}) {
    const Grown parallel = grow(program, 25, threads);
    EXPECT_EQ(ran(parallel), "serial 25") << threads << " threads";
    expectSameWords(*serial.world, *parallel.world, "context with choices on " + std::to_string(threads) + " threads");
    EXPECT_EQ(parallel.stats.cellsBorn, serial.stats.cellsBorn);
  }
}

TEST(ParallelRewrite, ChoicesAndStepsWhereSuccessorsExpireTakeTheSerialPass) {
  // A stochastic rule: the counts are not fixed per master.
  auto stochastic = testing_support::compileOrFail(R"(lsystem s {
  axiom A
  A -> A B : 0.5
  A -> B A : 0.5
  B -> B
})");
  ASSERT_NE(stochastic, nullptr);
  const Grown chosen = grow(stochastic, 17, 2);
  EXPECT_EQ(ran(chosen), "compact-serial 17");
  expectSameWords(*grow(stochastic, 17, 1, false).world, *chosen.world, "stochastic");

  // Steps of 2 s over lifetimes of 1 s: successors expire within the step. A word of
  // records takes the serial pass; Koch's compact word is rewritten instant by instant.
  auto koch = testing_support::compileOrFail(kKoch);
  const Grown serial = grow(koch, 8, 1, false);
  for (bool compact : {false, true}) {
    WorldDef def;
    def.threads = 2;
    def.recordLineage = !compact;  // a logged lineage keeps the records
    World world(koch, def);
    world.advanceTo(8, 2.0);
    EXPECT_EQ(world.rootPool().holdsCompactWord(), compact);
    EXPECT_EQ(world.rootPool().size(), 2u * 390625u - 1u);
    EXPECT_EQ(ran(world.stats()), compact ? "table-alone 7, table-bounds 1" : "serial 4") << "compact " << compact;
    expectSameWords(*serial.world, world, compact ? "compact Koch in steps of 2" : "Koch in steps of 2");
  }
}

// A world of `program` on `threads`, by slices or not, of at most `maxCells` cells.
World limitedWorld(const std::shared_ptr<const Program>& program, unsigned threads, bool slices, uint64_t maxCells) {
  WorldDef def;
  def.threads = threads;
  def.rewriteBySlices = slices;
  def.limits.maxCells = maxCells;
  return World(program, def);
}

// Koch past 100,000 cells at n = 7, from a word the serial pass writes; past 1,000,000 at
// n = 9, from a word of 781,249 modules rewritten by the table, which gives it up on the
// way. The message is the serial pass's, whatever the threads.
TEST(ParallelRewrite, ALimitIsReportedAsTheSerialPassReportsIt) {
  auto program = testing_support::compileOrFail(kKoch);
  for (const uint64_t limit : {100'000u, 1'000'000u}) {
    std::string reference;
    for (const bool slices : {false, true})
      for (unsigned threads : {1u, 2u}) {
        World world = limitedWorld(program, threads, slices, limit);
        try {
          if (limit > 100'000u) {  // n = 8 by the table (from 156,249 modules)
            world.advanceTo(8, 1.0);
            EXPECT_EQ(ran(world.stats()), !slices        ? "serial 8"
                                          : threads == 1 ? "table-alone 8"
                                                         : "table-alone 7, table-bounds 1")
                << threads << " threads, slices " << slices;
          }
          world.advanceTo(10, 1.0);
          ADD_FAILURE() << "no limit on " << threads << " threads";
        } catch (const LimitError& error) {
          if (reference.empty()) reference = error.what();
          EXPECT_EQ(error.what(), reference) << threads << " threads, slices " << slices;
          EXPECT_NE(reference.find(std::to_string(limit) + " cells"), std::string::npos) << error.what();
        }
      }
  }
}

// A word whose choice varies with its context doubles every step. On one thread, past its
// first large word, the compact pass writes it in one pass and asks the limits on the way
// (every 2^16 modules), so the step that passes maxCells is refused there, in the middle
// of the word; the limit is then reported as the records' serial pass reports it, on one
// thread and on two (by slices, refused after counting).
TEST(ParallelRewrite, ALimitPassedInTheMiddleOfAOnePassWordIsReportedAsTheSerialPassReportsIt) {
  auto program = testing_support::compileOrFail("lsystem g {\n  axiom a\n  ∅ < a -> b a\n  a -> a a\n  b -> b\n}\n");
  ASSERT_NE(program, nullptr);
  std::string reference;
  for (const bool slices : {false, true})
    for (unsigned threads : {1u, 2u}) {
      World world = limitedWorld(program, threads, slices, 400'000);
      world.advanceTo(19, 1.0);  // b a ... a: 2^(n - 1) + 1 modules at n
      ASSERT_EQ(world.rootPool().size(), 262'145u);
      EXPECT_EQ(world.rootPool().holdsCompactWord(), slices);
      EXPECT_EQ(ran(world.stats()), !slices        ? "serial 19"
                                    : threads == 1 ? "compact-serial 19"
                                                   : "compact-serial 16, parts 3")
          << threads << " threads, slices " << slices;
      try {
        world.advanceTo(20, 1.0);
        ADD_FAILURE() << "no limit on " << threads << " threads";
      } catch (const LimitError& error) {
        if (reference.empty()) reference = error.what();
        EXPECT_EQ(error.what(), reference) << threads << " threads, slices " << slices;
        EXPECT_NE(reference.find("400000 cells"), std::string::npos) << reference;
      }
    }
}

// A one-for-one word is written in place when its bounds fit the limits: every module
// expiring, each giving birth to one. The signal of 50,000 modules expires every module
// every step, so 50,000 events a step fit a limit of 60,000 and pass one of 40,000, which
// is then reported as the records' serial pass reports it, on one thread and on two.
TEST(ParallelRewrite, AOneForOneWordPastTheEventLimitIsReportedAsTheSerialPassReportsIt) {
  auto program = testing_support::compileOrFail(signalProgram(50'000));
  ASSERT_NE(program, nullptr);
  std::string reference;
  for (const uint64_t limit : {60'000u, 40'000u})
    for (const bool slices : {false, true})
      for (unsigned threads : {1u, 2u}) {
        WorldDef def;
        def.threads = threads;
        def.rewriteBySlices = slices;
        def.limits.maxEventsPerStep = limit;
        World world(program, def);
        try {
          world.advanceTo(5, 1.0);
          EXPECT_EQ(limit, 60'000u) << threads << " threads, slices " << slices;
          EXPECT_EQ(world.rootPool().holdsCompactWord(), slices);
          EXPECT_EQ(world.stats().events, 250'000u);
        } catch (const LimitError& error) {
          EXPECT_EQ(limit, 40'000u) << error.what();
          if (reference.empty()) reference = error.what();
          EXPECT_EQ(error.what(), reference) << threads << " threads, slices " << slices;
          EXPECT_NE(reference.find("40000"), std::string::npos) << reference;
        }
      }
  EXPECT_FALSE(reference.empty());
}

}  // namespace
}  // namespace ontogen
