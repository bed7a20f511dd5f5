// System hierarchies (paper 002, section 2.2): nested pools, reads of the enclosing
// systems, dynamic creation and the interpretation walk through the tree.

#include <gtest/gtest.h>

#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "core/word.h"
#include "core/world.h"
#include "interpreters/interpret.h"
#include "interpreters/text/word_text.h"
#include "test_support.h"

namespace ontogen {
namespace {

using testing_support::compileModel;

const WordCell* findLabel(const std::vector<WordCell>& word, const std::string& label, size_t nth = 0) {
  for (const WordCell& cell : word)
    if (cell.label == label && nth-- == 0) return &cell;
  return nullptr;
}

// The orchard: orchard > tree > branch. Branch lengths come from the tree's height and
// the orchard's wind; shoots grow towards their branch's length.
TEST(Hierarchy, OrchardIsThreeSystemsDeepAndReadsEveryLevel) {
  auto program = compileModel("orchard.cell");
  World world(program);
  world.advanceTo(14, program->dt);
  const auto word = captureWord(world);
  ASSERT_EQ(word.size(), 5u);  // tree Gap tree Gap tree
  const WordCell* tree = findLabel(word, "tree", 1);
  ASSERT_NE(tree, nullptr);
  EXPECT_DOUBLE_EQ(tree->params[0], 7);
  // Four pairs of branches, the n-th of length 7 * 0.45 * (1 - 0.25 * n / 2).
  std::vector<double> lengths;
  for (const WordCell& cell : tree->pool)
    if (cell.label == "branch") lengths.push_back(cell.params[0]);
  ASSERT_EQ(lengths.size(), 8u);
  for (int n = 0; n < 4; ++n) {
    const double expected = 7 * 0.45 * (1 - 0.25 * n / 2);
    EXPECT_NEAR(lengths[2 * n], expected, 1e-12) << n;
    EXPECT_NEAR(lengths[2 * n + 1], expected, 1e-12) << n;
  }
  // The first branch's shoot has grown to within 1% of its branch's length (rate 0.6
  // for 12 time units: e^-7.2 of the way left).
  const WordCell* first = findLabel(tree->pool, "branch");
  const WordCell* shoot = findLabel(first->pool, "Shoot");
  ASSERT_NE(shoot, nullptr);
  EXPECT_NEAR(shoot->params[0], first->params[0], 0.01 * first->params[0]);
  EXPECT_LT(shoot->params[0], first->params[0]);
  // Trunk segments approach a quarter of the tree's height.
  const WordCell* trunk = findLabel(tree->pool, "Trunk");
  EXPECT_NEAR(trunk->params[0], 7.0 / 4, 1e-3);
  // The orchard's 5 cells; per tree 4 x (Trunk [ + branch ] [ - branch ]) Trunk Bud = 38
  // cells and 8 branches of Shoot Leaf = 16 cells.
  EXPECT_EQ(world.totalCells(), 5u + 3 * (38 + 16));
}

// Records what an interpretation set is asked to do.
class RecordingSet final : public InterpretationSet {
 public:
  explicit RecordingSet(bool wantsIds = true) : wantsIds_(wantsIds) {}
  std::string_view name() const override { return "geometry"; }
  bool knows(std::string_view command) const override { return command == "F" || command == "f" || command == "D"; }
  bool wantsIds() const override { return wantsIds_; }
  void beginFrame(const FrameTarget&) override {}
  void execute(std::string_view command, std::span<const double> args) override {
    std::string entry(command);
    for (double a : args) entry += " " + std::to_string(static_cast<int>(a));
    log.push_back(entry);
  }
  std::vector<std::filesystem::path> endFrame() override { return {}; }
  std::vector<std::string> log;

 private:
  bool wantsIds_;
};

// A system cell's pool is realised as a branch where the cell stands, after the cell.
// The world of `source` at time `until`, or null (a failure added) when it does not compile.
std::unique_ptr<World> grownWorld(const std::string& source, double until) {
  DiagnosticSink sink;
  auto program = compileSource("world.cell", source, sink);
  if (!program) {
    ADD_FAILURE() << formatDiagnostics(sink);
    return nullptr;
  }
  auto world = std::make_unique<World>(std::shared_ptr<const Program>(std::move(program)));
  world->advanceTo(until, 1);
  return world;
}

TEST(Hierarchy, InterpretationWalksTheTreeAsBranches) {
  const std::unique_ptr<World> world = grownWorld(
      "system top { pool linear; axiom F(1) sub(2) F(3); }\n"
      "system sub(w = 0) { pool linear; axiom F(4) inner; }\n"
      "system inner { pool linear; axiom C; }\n"
      "cell C { interpret geometry { F(root.age + parent.parent.w * 10) } }\n",
      2);
  ASSERT_NE(world, nullptr);
  RecordingSet set;
  interpretWord(*world, set);
  EXPECT_EQ(set.log, (std::vector<std::string>{"F 1", "[", "F 4", "[", "F 22", "]", "]", "F 3"}));
}

// A set that reads no ids (the geometry set without scene nodes) is interpreted as one
// that does: the ids a word's cells need are computed for them whatever the set reads.
// A system cell's id finds its pool, an interpretation block's random stream and a
// development function's are keyed by the cell's id, so two cells of one master draw
// different numbers.
TEST(Hierarchy, CellsThatReadTheirIdsAreInterpretedAsWellForASetThatReadsNone) {
  const std::unique_ptr<World> world = grownWorld(
      "system top { pool linear; axiom F(1) sub(2) R R D(1) D(1); }\n"
      "system sub(w = 0) { pool linear; axiom F(4); }\n"
      "cell R { interpret geometry { F(uniform(0, 1000)) } }\n"
      "cell D(x = 0) { }\n"
      "g D(x) = uniform(1, 1000)\n",
      1);
  ASSERT_NE(world, nullptr);
  RecordingSet readingIds(true), readingNone(false);
  interpretWord(*world, readingIds);
  interpretWord(*world, readingNone);
  ASSERT_EQ(readingIds.log.size(), 8u);
  EXPECT_EQ(std::vector<std::string>(readingIds.log.begin(), readingIds.log.begin() + 4),
            (std::vector<std::string>{"F 1", "[", "F 4", "]"}));
  EXPECT_NE(readingIds.log[4], readingIds.log[5]) << "R draws by its id";
  EXPECT_NE(readingIds.log[6], readingIds.log[7]) << "D develops by its id";
  EXPECT_EQ(readingNone.log, readingIds.log);
}

// Systems created by an action get their pool at the end of that step, and the same
// program and seed give the same nested words on any number of threads.
TEST(Hierarchy, DynamicSystemsAreReproducibleAcrossThreads) {
  DiagnosticSink sink;
  auto program = compileSource("dyn.cell",
                               "system top { pool linear; axiom S; }\n"
                               "system colony(k = 0) { pool linear; axiom A; }\n"
                               "cell S(n = 0) { rules { n < 3 : n += 1, -> me colony(uniform(0, 1)); } }\n"
                               "cell A(x = 0) { rules { x < 20 : -> A(x + gaussian()) A(x + 1 + parent.k); } }\n",
                               sink);
  ASSERT_NE(program, nullptr) << formatDiagnostics(sink);
  std::shared_ptr<const Program> shared(std::move(program));
  auto grow = [&](unsigned threads) {
    WorldDef def;
    def.threads = threads;
    World world(shared, def);
    world.advanceTo(6, 1);
    std::ostringstream json;
    writeWordJson(json, {WordAtTime{world.time(), captureWord(world)}});
    return json.str();
  };
  const std::string one = grow(1);
  EXPECT_EQ(one, grow(2));
  EXPECT_EQ(one, grow(1));
  EXPECT_NE(one.find("\"pool\""), std::string::npos);
  // Three colonies, each with its own draws: their pools differ.
  World world(shared);
  world.advanceTo(6, 1);
  const auto word = captureWord(world);
  ASSERT_EQ(word.size(), 4u);
  EXPECT_EQ(word[0].label, "S");
  EXPECT_NE(formatWord(word[1].pool), formatWord(word[2].pool));
}

}  // namespace
}  // namespace ontogen
