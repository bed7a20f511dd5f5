// The example models of models/: their words and their geometry, by value.

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <complex>
#include <filesystem>

#include "core/word.h"
#include "core/world.h"
#include "interpreters/geometry/geometry_set.h"
#include "interpreters/interpret.h"
#include "interpreters/text/word_text.h"
#include "test_support.h"

namespace ontogen {
namespace {

using testing_support::compileModel;

std::string labels(const World& world) {
  std::string text;
  for (const WordCell& cell : captureWord(world)) text += cell.label;
  return text;
}

// Interprets the world with the geometry set without writing files.
struct Drawn {
  size_t segments = 0;
  glm::dvec3 end{0.0};
};

Drawn draw(const World& world) {
  GeometrySetDef def;
  const InterpretSettings& settings = world.rootSystem().settings;
  def.turtle.angle = settings.angle;
  def.turtle.yawAngle = settings.yawAngle;
  def.turtle.step = settings.step;
  def.turtle.radius = settings.radius;
  def.turtle.radians = settings.radians;
  GeometrySet set(def);
  set.beginFrame(FrameTarget{});
  interpretWord(world, set);
  return {set.geometry().segmentCount() + set.geometry().cylinders().size(), set.turtle().state().position};
}

TEST(Models, ThueMorseGenerations) {
  World world(compileModel("thue_morse.cell"));
  const char* expected[] = {"a", "ab", "abba", "abbabaab", "abbabaabbaababba"};
  for (int n = 0; n <= 4; ++n) {
    world.advanceTo(n, 1);
    EXPECT_EQ(labels(world), expected[n]) << "generation " << n;
  }
  world.advanceTo(12, 1);
  EXPECT_EQ(world.rootPool().size(), 4096u);
  // The n-th symbol is the parity of the number of ones in n's binary form.
  auto word = captureWord(world);
  for (size_t i = 0; i < word.size(); ++i) ASSERT_EQ(word[i].label, std::popcount(i) % 2 ? "b" : "a") << i;
}

TEST(Models, DragonCurveSegmentsAndEndPoint) {
  World world(compileModel("dragon.cell"));
  for (int n : {1, 4, 10}) {
    world.advanceTo(n, 1);
    Drawn drawn = draw(world);
    EXPECT_EQ(drawn.segments, 1u << n) << "generation " << n;
    // With + a left turn (multiplication by i) and the first step along +y (i), the end
    // is (1 + i)^n * i.
    std::complex<double> end = std::pow(std::complex<double>(1, 1), n) * std::complex<double>(0, 1);
    EXPECT_NEAR(drawn.end.x, end.real(), 1e-9) << "generation " << n;
    EXPECT_NEAR(drawn.end.y, end.imag(), 1e-9) << "generation " << n;
  }
}

TEST(Models, KochCurveSegmentsAndReach) {
  World world(compileModel("koch.cell"));
  world.advanceTo(5, 1);
  Drawn drawn = draw(world);
  EXPECT_EQ(drawn.segments, 3125u);  // 5^5
  EXPECT_NEAR(drawn.end.x, 0, 1e-9);
  EXPECT_NEAR(drawn.end.y, 243, 1e-9);  // 3^5 along the first heading
}

TEST(Models, BranchingSegmentsAndBalancedBrackets) {
  World world(compileModel("branching.cell"));
  world.advanceTo(4, 1);
  EXPECT_EQ(draw(world).segments, 625u);  // 5^4
  int depth = 0;
  for (const WordCell& cell : captureWord(world)) {
    depth += cell.label == "[" ? 1 : cell.label == "]" ? -1 : 0;
    ASSERT_GE(depth, 0);
  }
  EXPECT_EQ(depth, 0);
}

TEST(Models, AnabaenaFollowsAbopGenerations) {
  World world(compileModel("anabaena.cell"));
  const char* expected[] = {"ar", "albr", "blarar", "alalbralbr", "blarblararblarar"};
  for (int n = 0; n <= 4; ++n) {
    world.advanceTo(n, 0.25);
    EXPECT_EQ(labels(world), expected[n]) << "generation " << n;
  }
  // The counts follow Fibonacci's sequence.
  size_t previous = 5, current = 8;
  for (int n = 5; n <= 12; ++n) {
    world.advanceTo(n, 0.5);
    size_t next = previous + current;
    previous = current;
    current = next;
    EXPECT_EQ(world.rootPool().size(), current) << "generation " << n;
  }
}

TEST(Models, AnabaenaCellsGrowContinuouslyBetweenDivisions) {
  World world(compileModel("anabaena.cell"));
  world.advanceTo(0.5, 0.5);
  Drawn half = draw(world);
  // ar at age 0.5: F(0.6 + 0.15) f(0.1)
  EXPECT_NEAR(half.end.y, 0.85, 1e-12);
}

TEST(Models, PistonDrawsItsParts) {
  World world(compileModel("piston.cell"));
  world.advanceTo(1.04, 0.04);
  GeometrySet set;
  set.beginFrame(FrameTarget{});
  interpretWord(world, set);
  EXPECT_EQ(set.geometry().cylinders().size(), 2u);  // piston and connecting rod
  EXPECT_EQ(set.geometry().discs().size(), 1u);      // the flywheel
  EXPECT_NEAR(set.geometry().cylinders()[0].radius, 10, 1e-12);
  EXPECT_NEAR(set.geometry().cylinders()[1].radius, 2, 1e-12);
}

// Every model's pools read the same through the cursor and through cellAt as the records
// of the same model grown without the rewriting by slices (which keeps every word in
// records), nested pools included: the layer readers outside pools/ and core/ use, and
// the compact words of label-only models (docs/COMPACT_WORDS.md), change nothing they see.
size_t expectCursorAgrees(const World& world, const World& reference, const std::string& where, size_t& compactPools) {
  const Pool& pool = world.rootPool();
  const Pool& recordsPool = reference.rootPool();
  EXPECT_FALSE(recordsPool.holdsCompactWord()) << where;
  if (pool.holdsCompactWord()) ++compactPools;
  const auto records = recordsPool.cells();
  const auto& masters = world.program().masters;
  size_t cells = 0;
  size_t index = 0;
  for (CellCursor cursor = pool.cursor(); !cursor.done(); cursor.next(), ++index) {
    EXPECT_LT(index, records.size()) << where;
    if (index >= records.size()) break;
    const CellRecord& record = records[index];
    const CellView view = cursor.view();
    const CellView at = pool.cellAt(index);
    for (const CellView& cell : {view, at}) {
      EXPECT_EQ(cell.index, index) << where;
      EXPECT_EQ(cell.master, record.master) << where << ", cell " << index;
      EXPECT_EQ(cell.id, record.id) << where << ", cell " << index;
      EXPECT_EQ(std::bit_cast<uint64_t>(cell.birth), std::bit_cast<uint64_t>(record.birth))
          << where << ", cell " << index;
      const double* expected = recordsPool.stateOf(record);
      for (uint32_t k = 0; k < masters[record.master].stateCount(); ++k)
        EXPECT_EQ(std::bit_cast<uint64_t>(cell.state[k]), std::bit_cast<uint64_t>(expected[k]))
            << where << ", cell " << index << ", value " << k;
      if (!pool.holdsCompactWord()) {
        EXPECT_EQ(cell.state, pool.stateOf(pool.cells()[index])) << where;
      }
    }
    EXPECT_EQ(cursor.master(), record.master);
    EXPECT_EQ(cursor.id(), record.id);
    const World* child = world.childOf(cursor.id());
    const World* referenceChild = reference.childOf(cursor.id());
    EXPECT_EQ(child == nullptr, referenceChild == nullptr) << where << ", cell " << index;
    if (child && referenceChild)
      cells += expectCursorAgrees(*child, *referenceChild, where + " > " + masters[record.master].label, compactPools);
  }
  EXPECT_EQ(index, records.size()) << where;
  return cells + index;
}

TEST(Models, EveryModelReadsTheSameThroughTheCursor) {
  namespace fs = std::filesystem;
  size_t models = 0, compactPools = 0;
  for (const auto& entry : fs::directory_iterator(fs::path(ONTOGEN_SOURCE_DIR) / "models")) {
    if (entry.path().extension() != ".cell") continue;
    const std::string name = entry.path().filename().string();
    // By its full path: some models read files beside them.
    auto program = testing_support::compileOrFail(testing_support::readModel(name), entry.path().string());
    ASSERT_NE(program, nullptr) << name;
    ++models;
    WorldDef recordsDef;
    recordsDef.rewriteBySlices = false;
    World world(program), reference(program, recordsDef);
    // A few of each model's own steps: enough for successors, state and nested pools.
    const double until = std::min(program->until, std::max(8 * program->dt, 4.0));
    world.advanceTo(until, program->dt);
    reference.advanceTo(until, program->dt);
    const size_t before = compactPools;
    EXPECT_GT(expectCursorAgrees(world, reference, name, compactPools), 0u) << name;
    if (name == "koch.cell") {
      EXPECT_EQ(compactPools, before + 1) << "Koch's word is kept compact";
    }
  }
  EXPECT_GE(models, 30u);
}

}  // namespace
}  // namespace ontogen
