// Scenes (interpreters/scene.h): the geometry set draws a node per cell keyed by its
// stable id, with its parent, where the turtle stood and what it drew; several sets draw
// into one frame's scene, which the run's output stage writes.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/parents.h"
#include "interpreters/geometry/geometry_set.h"
#include "interpreters/geometry/turtle_commands.h"
#include "interpreters/interpret.h"
#include "interpreters/run.h"
#include "tests/core/test_support.h"

namespace ontogen {
namespace {

namespace fs = std::filesystem;

TEST(Scene, ANodePerDrawingCellWithItsIdParentAndPlace) {
  auto program = testing_support::compileOrFail("lsystem t {\n  axiom F(1) [ + F(2) ] F(3)\n}");
  World world(program);
  GeometrySet set(GeometrySetDef{.sceneNodes = true});
  set.beginFrame({});
  interpretWord(world, set);
  Scene scene;
  set.contribute(scene);
  const auto cells = world.rootPool().cells();
  ASSERT_EQ(scene.nodes.size(), 3u) << "the F's draw; brackets and + do not";
  const SceneNode& first = scene.nodes[0];
  const SceneNode& branch = scene.nodes[1];
  const SceneNode& trunk = scene.nodes[2];
  EXPECT_EQ(first.id, cells[0].id);
  EXPECT_EQ(first.parent, kNoParentNode);
  EXPECT_EQ(branch.id, cells[3].id);
  EXPECT_EQ(branch.parent, cells[0].id) << "F(2) hangs from F(1)";
  EXPECT_EQ(trunk.id, cells[5].id);
  EXPECT_EQ(trunk.parent, cells[0].id) << "so does F(3)";
  // F(2) starts where F(1) ended, turned by +90 degrees; F(3) too, not turned.
  EXPECT_NEAR(branch.position.y, 1, 1e-12);
  EXPECT_NEAR(trunk.position.y, 1, 1e-12);
  EXPECT_NEAR(glm::length(branch.orientation[0] - glm::dvec3(-1, 0, 0)), 0, 1e-12) << "heading after +";
  EXPECT_NEAR(glm::length(trunk.orientation[0] - glm::dvec3(0, 1, 0)), 0, 1e-12);
  for (const SceneNode& node : scene.nodes) EXPECT_EQ(node.range.segmentCount, 1u);
  EXPECT_EQ(scene.geometry.segments()[branch.range.firstSegment].end.x, -2.0);
  EXPECT_EQ(scene.find(cells[5].id), &trunk);
  for (const SceneNode& node : scene.nodes) {
    EXPECT_EQ(node.label, "F") << "the master's label";
    EXPECT_EQ(node.birth, 0.0) << "the axiom's cells are born at 0";
  }
}

// A set of the test's own that draws a marker line under every cell beside the turtle.
class MarkerSet final : public InterpretationSet {
 public:
  std::string_view name() const override { return "geometry"; }
  bool knows(std::string_view command) const override { return command == "F"; }
  void beginFrame(const FrameTarget&) override { drawn_.clear(); }
  void execute(std::string_view, std::span<const double>) override {
    const double x = static_cast<double>(drawn_.geometry.segmentCount());
    drawn_.geometry.addSegment({x, -1, 0}, {x + 0.5, -1, 0});
  }
  std::vector<fs::path> endFrame() override { return {}; }
  bool drawsScene() const override { return true; }
  void contribute(Scene& scene) override { scene.append(drawn_); }

 private:
  Scene drawn_;
};

// Homomorphism rules (docs/LANGUAGE.md 4.9): the set draws the image, N -> F F, while
// the word keeps its N's; the image's F's stand where their N stands in the tree.
TEST(Scene, TheGeometrySetDrawsTheHomomorphismsImage) {
  auto program = testing_support::compileOrFail("lsystem t {\n  axiom N [ + N ]\n  homomorphism:\n  N -> F F\n}");
  World world(program);
  ASSERT_EQ(world.rootPool().size(), 5u);
  GeometrySet set(GeometrySetDef{.sceneNodes = true});
  set.beginFrame({});
  interpretWord(world, set);
  Scene scene;
  set.contribute(scene);
  ASSERT_EQ(scene.nodes.size(), 4u) << "two F's for each N";
  const uint64_t trunk = world.rootPool().cells()[0].id;
  EXPECT_EQ(scene.nodes[0].parent, kNoParentNode);
  EXPECT_EQ(scene.nodes[2].parent, trunk) << "the image of the branch's N hangs where that N hangs";
  for (const SceneNode& node : scene.nodes) EXPECT_NE(node.id, trunk) << "ids of their own";
}

TEST(Scene, TwoSetsDrawIntoOneFrameAndTheOutputStageWritesIt) {
  RunDef def;
  def.program = testing_support::compileOrFail("lsystem t {\n  axiom F F F\n}");
  def.stem = "both";
  def.until = 0;
  def.setOptions.formats = "obj";
  def.out = fs::path(ONTOGEN_BINARY_DIR) / "scene_test";
  fs::remove_all(def.out);
  ontogen::Run run(std::move(def));
  run.sets().push_back(std::make_unique<MarkerSet>());
  const RunReport report = run.execute();
  ASSERT_TRUE(report.ok());
  ASSERT_EQ(report.files.size(), 2u) << "one OBJ (and its MTL) for the frame both sets drew";
  ASSERT_EQ(report.files[0].extension(), ".obj");
  std::ifstream in(report.files[0]);
  int lines = 0;
  for (std::string line; std::getline(in, line);) lines += line.rfind("l ", 0) == 0;
  EXPECT_EQ(lines, 6) << "three F's of the turtle and three markers";
}

// A set hands an empty scene its buffers and copies into one that holds something, its
// nodes' ranges shifted past what is there: both give what copying gives, segments,
// spheres' triangles, nodes and bounds alike, and the set draws its next frame afresh.
TEST(Scene, ContributingTakesTheSetsBuffersOrCopiesThemAlike) {
  auto program = testing_support::compileOrFail(
      "lsystem t {\n  axiom F(1) [ + F(2) ] A F(3)\n  interpret geometry A { sphere(0.5) }\n}");
  World world(program);
  GeometrySet set(GeometrySetDef{.sceneNodes = true});
  auto drawn = [&] {
    set.beginFrame({});
    interpretWord(world, set);
  };
  // The copy: another set's finished scene appended as a const scene.
  GeometrySet other(GeometrySetDef{.sceneNodes = true});
  other.beginFrame({});
  interpretWord(world, other);
  Scene finished;
  other.contribute(finished);
  Scene copied;
  copied.append(static_cast<const Scene&>(finished));
  drawn();
  Scene taken;
  set.contribute(taken);
  ASSERT_GE(copied.nodes.size(), 3u);
  ASSERT_GT(copied.geometry.triangleCount(), 0u);
  auto same = [](const Scene& a, const Scene& b, std::size_t from) {
    ASSERT_EQ(a.geometry.segmentCount(), b.geometry.segmentCount() - 3 * from);
    for (std::size_t s = 0; s < a.geometry.segmentCount(); ++s) {
      EXPECT_EQ(a.geometry.segments()[s].start, b.geometry.segments()[3 * from + s].start);
      EXPECT_EQ(a.geometry.segments()[s].end, b.geometry.segments()[3 * from + s].end);
    }
    ASSERT_EQ(b.nodes.size(), a.nodes.size() * (from + 1));
    const std::size_t triangles = from * a.geometry.triangleCount();
    for (std::size_t n = 0; n < a.nodes.size(); ++n) {
      const SceneNode& x = a.nodes[n];
      const SceneNode& y = b.nodes[from * a.nodes.size() + n];
      EXPECT_EQ(x.id, y.id);
      EXPECT_EQ(x.label, y.label);
      EXPECT_EQ(x.range.firstSegment + 3 * from, y.range.firstSegment);
      EXPECT_EQ(x.range.firstTriangle + triangles, y.range.firstTriangle);
      EXPECT_EQ(x.range.segmentCount, y.range.segmentCount);
      EXPECT_EQ(x.range.triangleCount, y.range.triangleCount);
    }
    EXPECT_EQ(b.geometry.spheres().size(), a.geometry.spheres().size() * (from + 1));
    EXPECT_EQ(b.geometry.triangleCount(), a.geometry.triangleCount() * (from + 1));
  };
  same(copied, taken, 0);
  EXPECT_EQ(taken.geometry.bounds().min, copied.geometry.bounds().min);
  EXPECT_EQ(taken.geometry.bounds().max, copied.geometry.bounds().max);
  EXPECT_TRUE(set.scene().nodes.empty() && set.scene().geometry.empty()) << "the set's scene handed over";
  // The next frame, into the scene that holds the first: copied after it.
  drawn();
  ASSERT_EQ(set.scene().nodes.size(), copied.nodes.size() - 1) << "drawn afresh (the last node closes at the end)";
  set.contribute(taken);
  same(copied, taken, 1);
}

// A word's lines are written into room reserved once for the word (a line per cell at
// most, for lines drawn by symbols), not into a vector regrown by doubling: ABOP Fig. 1.24
// (d) at n = 12 draws a million lines, and each regrowth copied them into fresh pages.
TEST(Scene, ASetsLinesGoIntoRoomReservedForTheWord) {
  std::string axiom;
  for (int i = 0; i < 100; ++i) axiom += " F(1) [ + ]";
  auto program = testing_support::compileOrFail("lsystem t {\n  axiom" + axiom + "\n}");
  World world(program);
  const std::size_t cells = world.rootPool().size();
  ASSERT_EQ(cells, 400u);
  for (const bool nodes : {false, true}) {
    GeometrySet set(GeometrySetDef{.sceneNodes = nodes});
    set.beginFrame({});
    interpretWord(world, set);
    ASSERT_EQ(set.scene().geometry.segmentCount(), 100u);
    // Grown by doubling, 100 lines would sit in room for 128.
    EXPECT_GE(set.scene().geometry.segments().capacity(), cells) << "nodes " << nodes;
    EXPECT_EQ(set.scene().geometry.segments()[99].start, glm::dvec3(0, 99, 0));
  }
}

// A word grown without ids (docs/COMPACT_WORDS.md, "Words without ids") is drawn as it is
// held when the set reads no ids and nothing else does (parents, a homomorphism,
// interpretation blocks, development functions, nested pools): the pool's replay, which
// makes the ids again and costs several times the derivation, does not run.
TEST(Scene, AWordGrownWithoutIdsIsDrawnWithoutMakingItsIdsAgain) {
  auto program = testing_support::compileOrFail("lsystem koch {\n  #angle 90\n  axiom F\n  F -> F + F - F - F + F\n}");
  auto drawn = [&](bool withoutIds, bool nodes) {
    WorldDef def;
    def.wordsWithoutIds = withoutIds;
    auto world = std::make_unique<World>(program, def);
    world->advanceTo(7, 1);
    EXPECT_EQ(world->rootPool().holdsIds(), !withoutIds) << "grown " << (withoutIds ? "without" : "with") << " ids";
    GeometrySet set(GeometrySetDef{.sceneNodes = nodes});
    set.beginFrame({});
    interpretWord(*world, set);
    EXPECT_EQ(world->rootPool().holdsIds(), !withoutIds || nodes)
        << (nodes ? "a set that records nodes reads ids: they are made again"
                  : "a set that reads no ids draws the word as it is held");
    Scene scene;
    set.contribute(scene);
    return scene;
  };
  const Scene asHeld = drawn(true, false);
  const Scene withIds = drawn(false, false);
  const Scene replayed = drawn(true, true);
  ASSERT_EQ(asHeld.geometry.segmentCount(), 78'125u) << "5^7 lines";
  for (const Scene* other : {&withIds, &replayed}) {
    ASSERT_EQ(other->geometry.segmentCount(), asHeld.geometry.segmentCount());
    for (std::size_t i = 0; i < asHeld.geometry.segmentCount(); ++i) {
      const Segment& a = asHeld.geometry.segments()[i];
      const Segment& b = other->geometry.segments()[i];
      ASSERT_TRUE(a.start == b.start && a.end == b.end && a.material == b.material) << "line " << i;
    }
  }
  EXPECT_NEAR(glm::length(asHeld.geometry.segments().back().end - glm::dvec3(0, 2187, 0)), 0, 1e-6)
      << "3^7 units along the first heading";
}

// The compiler resolves every instruction to its set's command once: the interpreter hands
// the set numbers, never a name to look up, for blocks and for symbols alike.
class CountingSet final : public InterpretationSet {
 public:
  std::string_view name() const override { return "geometry"; }
  bool knows(std::string_view) const override { return true; }
  void beginFrame(const FrameTarget&) override {}
  void execute(std::string_view, std::span<const double>) override { ++byName; }
  void executeCommand(int id, std::string_view command, std::span<const double>) override {
    ids.push_back(id);
    names.push_back(std::string(command));
  }
  std::vector<fs::path> endFrame() override { return {}; }
  int byName = 0;
  std::vector<int> ids;
  std::vector<std::string> names;
};

TEST(Scene, CommandsAreResolvedOnceByTheCompiler) {
  auto program = testing_support::compileOrFail(
      "lsystem t {\n  axiom F(1) + A\n  interpret geometry A { f(2) sphere(1) }\n}");
  const int geometry = program->commandSetIndex("geometry");
  ASSERT_GE(geometry, 0);
  const auto table = turtleCommands();
  auto idOf = [&](std::string_view name) {
    for (size_t i = 0; i < table.size(); ++i)
      if (table[i].name == name) return static_cast<int>(i);
    return -1;
  };
  const int f = program->findMaster("F", 0);
  ASSERT_GE(f, 0);
  EXPECT_EQ(program->masters[f].commandIds[geometry], idOf("F"));
  World world(program);
  CountingSet set;
  interpretWord(world, set);
  EXPECT_EQ(set.byName, 0) << "nothing goes by name";
  EXPECT_EQ(set.ids, (std::vector<int>{idOf("F"), idOf("+"), idOf("f"), idOf("sphere")}));
  EXPECT_EQ(set.names, (std::vector<std::string>{"F", "+", "f", "sphere"}));
}

}  // namespace
}  // namespace ontogen
