// Who hangs from whom (core/parents.h): ABOP's axial tree in bracketed words, chains in
// filaments, system cells above nested pools, ids kept by `=X` across rewrites, and the
// lineage log of births.

#include <gtest/gtest.h>

#include <algorithm>

#include "core/parents.h"
#include "core/word.h"
#include "interpreters/text/word_text.h"
#include "core/world.h"
#include "test_support.h"

namespace ontogen {
namespace {

using testing_support::compileOrFail;

std::vector<std::string> labels(const World& world) {
  std::vector<std::string> out;
  for (const CellRecord& cell : world.rootPool().cells()) out.push_back(world.program().masters[cell.master].label);
  return out;
}

TEST(Parents, BranchesHangFromTheNodeBeforeTheirBracket) {
  World world(compileOrFail("lsystem t {\n  axiom F(1) [ + F(2) [ - A ] B ] F(3) C\n}"));
  ASSERT_EQ(labels(world), (std::vector<std::string>{"F", "[", "+", "F", "[", "-", "A", "]", "B", "]", "F", "C"}));
  const std::vector<int64_t> parents = parentIndices(world);
  //                                   F   [  +  F  [  -  A  ]  B  ]  F   C
  EXPECT_EQ(parents, (std::vector<int64_t>{-1, 0, 0, 0, 3, 3, 3, 3, 3, 0, 0, 10}));
  const std::vector<uint64_t> ids = parentIds(world);
  EXPECT_EQ(ids[0], kNoParent);
  EXPECT_EQ(ids[3], world.rootPool().cells()[0].id) << "F(2) hangs from F(1)";
  EXPECT_EQ(ids[10], world.rootPool().cells()[0].id) << "F(3) hangs from F(1)";
}

TEST(Parents, AFilamentIsAChainAndANestedPoolHangsFromItsSystemCell) {
  World world(compileOrFail("system inner { pool linear; axiom A B; }\n"
                            "system outer { pool linear; axiom X inner Y; }\n"
                            "cell A { } cell B { } cell X { } cell Y { }",
                            "nested.cell"));
  EXPECT_EQ(parentIndices(world), (std::vector<int64_t>{-1, 0, 1}));
  const CellRecord& system = world.rootPool().cells()[1];
  const World* inner = world.childOf(system);
  ASSERT_NE(inner, nullptr);
  const std::vector<uint64_t> ids = parentIds(*inner);
  ASSERT_EQ(ids.size(), 2u);
  EXPECT_EQ(ids[0], system.id) << "the first cell of a nested pool hangs from its system cell";
  EXPECT_EQ(ids[1], inner->rootPool().cells()[0].id);
  const std::vector<WordCell> word = captureWord(world);
  EXPECT_EQ(word[1].pool[0].parent, system.id);
  EXPECT_EQ(word[0].parent, kNoParent);
}

TEST(Parents, GridCellsHangFromTheirSystemCellOnly) {
  World world(compileOrFail("cell C { } system g { pool grid(3); fill C; }"));
  EXPECT_EQ(parentIds(world), std::vector<uint64_t>(3, kNoParent));
}

// Paper 000 Fig. 9: a joint that goes sw -> su -> st through productions stays one joint.
TEST(Parents, AnIdentityKeptThroughRewritesAndTheLineageLog) {
  auto program = compileOrFail(
      "lsystem gait {\n  axiom F (sw, 0)\n  (sw, 1) -> =(su, 0)\n  (su, 1) -> =(st, 0) F\n  (st, 1) -> (sw, 0)\n}");
  WorldDef def;
  def.recordLineage = true;
  World world(program, def);
  const uint64_t joint = world.rootPool().cells()[1].id;
  world.advanceTo(1.5, 0.25);
  ASSERT_EQ(labels(world), (std::vector<std::string>{"F", "su"}));
  EXPECT_EQ(world.rootPool().cells()[1].id, joint) << "=su keeps sw's id";
  world.advanceTo(2.5, 0.25);
  ASSERT_EQ(labels(world), (std::vector<std::string>{"F", "st", "F"}));
  EXPECT_EQ(world.rootPool().cells()[1].id, joint) << "=st keeps it again";
  const uint64_t newF = world.rootPool().cells()[2].id;
  EXPECT_NE(newF, joint);
  world.advanceTo(3.5, 0.25);
  EXPECT_NE(world.rootPool().cells()[1].id, joint) << "a plain successor gets an id of its own";
  // The log: su and st kept the id, the F and the new sw were born of the joint.
  const auto& log = world.lineage();
  ASSERT_EQ(log.size(), 4u);
  EXPECT_EQ(log[0], (LineageRecord{joint, joint, 1.0}));
  EXPECT_EQ(log[1], (LineageRecord{joint, joint, 2.0}));
  EXPECT_EQ(log[2], (LineageRecord{newF, joint, 2.0}));
  EXPECT_EQ(log[3].parent, joint);
  EXPECT_DOUBLE_EQ(log[3].time, 3.0);
}

TEST(Parents, TheLineageOfPerStepBirthsInEveryPoolKind) {
  for (const char* pool : {"linear", "grid(4) closed vonneumann", "spatial(1)"}) {
    auto program = compileOrFail(std::string("cell A(x = 0) { rules { age > 0.5 && x == 0 : x = 1, -> me B; } }\n"
                                             "cell B { }\n system s { pool ") +
                                 pool + "; axiom A; }");
    WorldDef def;
    def.recordLineage = true;
    World world(program, def);
    const uint64_t a = world.rootPool().cells()[0].id;
    world.advanceTo(3, 1);
    ASSERT_EQ(world.rootPool().size(), 2u) << pool;
    const auto& log = world.lineage();
    ASSERT_EQ(log.size(), 1u) << pool;
    EXPECT_EQ(log[0].parent, a) << pool;
    EXPECT_DOUBLE_EQ(log[0].time, 1.0) << pool;
    const auto cells = world.rootPool().cells();
    EXPECT_TRUE(std::any_of(cells.begin(), cells.end(), [&](const CellRecord& c) { return c.id == log[0].child; }))
        << pool;
  }
}

// Rules read their parent's id as me.parent (paper 003's isChildOf): an A compares it with
// the id its left context F noted; the first cell has none (-1); a nested pool's first
// cell hangs from its system cell, whose id it is given.
TEST(Parents, RulesReadTheirParentAsMeParent) {
  auto program = compileOrFail(
      "cell F(f = -1) { rules { f < 0 : f = id; } }\n"
      "cell A(ok = 0) { rules { F(f) me : f >= 0 && ok == 0 : ok = if(me.parent == f, 1, 2); } }\n"
      "cell R(p = 0) { rules { p == 0 : p = if(me.parent == -1, 1, 2); } }\n"
      "system s { pool linear; axiom R F [ A ] A; }");
  World world(program);
  world.advanceTo(3, 1);
  ASSERT_EQ(labels(world), (std::vector<std::string>{"R", "F", "[", "A", "]", "A"}));
  const Pool& pool = world.rootPool();
  EXPECT_EQ(*pool.stateOf(pool.cells()[0]), 1) << "R has no parent";
  EXPECT_EQ(*pool.stateOf(pool.cells()[3]), 1) << "the A in the branch hangs from F";
  EXPECT_EQ(*pool.stateOf(pool.cells()[5]), 1) << "the A after it too";

  auto grid = compileOrFail("cell C(p = 0) { rules { p == 0 : p = me.parent; } }\n"
                            "system g { pool grid(2); fill C; }\n"
                            "system top { pool linear; axiom g; }", "nested.cell");
  World outer(grid);
  outer.advanceTo(2, 1);
  const CellRecord& system = outer.rootPool().cells()[0];
  const World* inner = outer.childOf(system);
  ASSERT_NE(inner, nullptr);
  for (const CellRecord& cell : inner->rootPool().cells())
    EXPECT_EQ(*inner->rootPool().stateOf(cell), idValue(system.id)) << "grid cells hang from their system cell";
}

}  // namespace
}  // namespace ontogen
