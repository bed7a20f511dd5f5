// The physics set as a program meets it: rods from rod, F and cC, parents along the
// word's branches by stable id, attributes pushed with [, the arrows drawn at the joints
// (scaled and coloured by magnitude), the deflected shape drawn when elastic, warnings
// located, frames that do not depend on the frames before; its command table is the
// one docs/LANGUAGE.md documents; a run writes the rods and arrows into one glTF that the
// Khronos validator accepts.

#include "interpreters/physics/physics_set.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include <glm/geometric.hpp>

#include "interpreters/palette.h"
#include "interpreters/physics/physics_commands.h"
#include "interpreters/run.h"
#include "tests/interpreters/external_tools.h"
#include "tests/interpreters/physics/physics_support.h"

namespace ontogen {
namespace {

namespace fs = std::filesystem;
using testing_support::compileModel;
using testing_support::compileOrFail;
using testing_support::runCommand;
using testing_support::solveModel;
using testing_support::solveText;

// A checker the test needs: missing, it skips on a developer's machine and fails in CI.
#define REQUIRE_CHECKER(available, what)                                               \
  do {                                                                                 \
    if (!(available)) {                                                                \
      const char* ci = std::getenv("CI");                                              \
      if (ci != nullptr && std::string(ci) == "true") FAIL() << what << " is missing"; \
      GTEST_SKIP() << what << " is missing (bash .ci/setup --checkers installs it)";   \
    }                                                                                  \
  } while (false)

void draw(PhysicsSet& set) {
  Scene scene;
  set.contribute(scene);
}

TEST(PhysicsSet, FAndCCAndRodMakeRodsThatHangAlongTheBranches) {
  const auto solved = solveText("lsystem a { axiom !(0.1) F(2) [ + cC(1, 1) ] - rod(3, 0.2, 4) }\n", 0);
  const PhysicsFrame& frame = solved.frame();
  ASSERT_EQ(frame.rods.size(), 3u);
  EXPECT_EQ(frame.rods[0].parent, kNoParentRod);
  EXPECT_EQ(frame.rods[1].parent, frame.rods[0].id) << "the branch hangs from the rod before its [";
  EXPECT_EQ(frame.rods[2].parent, frame.rods[0].id) << "after ], from the rod before the branch";
  EXPECT_NEAR(frame.rods[0].mass, std::numbers::pi * 0.01 * 2, 1e-12) << "F: the turtle's radius, density 1";
  EXPECT_NEAR(frame.rods[2].mass, 4 * std::numbers::pi * 0.04 * 3, 1e-12) << "rod's own radius and density";
  EXPECT_NEAR(frame.rods[2].base.y(), 2, 1e-12) << "a rod's base is where the turtle stood";
  std::set<uint64_t> ids;
  for (const RodResult& rod : frame.rods) ids.insert(rod.id);
  EXPECT_EQ(ids.size(), 3u) << "ids are distinct";
}

TEST(PhysicsSet, ACellOfTwoRodsGivesItsSecondAnIdOfItsOwn) {
  const auto solved = solveText(
      "cell Seg() { interpret physics { rod(1, 0.1, 1) rod(1, 0.1, 1) } }\nsystem s { pool linear; axiom Seg() Seg(); }\n", 0);
  const PhysicsFrame& frame = solved.frame();
  ASSERT_EQ(frame.rods.size(), 4u);
  EXPECT_NE(frame.rods[0].id, frame.rods[1].id);
  EXPECT_EQ(frame.rods[1].parent, frame.rods[0].id);
  EXPECT_EQ(frame.rods[2].parent, frame.rods[1].id) << "the next cell's rod hangs from the last rod before it";
}

TEST(PhysicsSet, AttributesArePushedWithBranchesAndLoadsGoToTheNextRod) {
  const auto solved = solveText(
      "lsystem a { axiom density(2) stiffness(5) [ density(7) young(100) rod(1, 0.5, 7) ] load(1, 0, 0, 0.25) rod(1, 0.5, 2) "
      "rod(1, 0.5, 2) }\n",
      0);
  const auto rods = solved.set->table().rods();
  ASSERT_EQ(rods.size(), 3u);
  EXPECT_NEAR(rods[0].stiffness, 100 * std::numbers::pi * std::pow(0.5, 4) / 4, 1e-12) << "EI = E pi r^4 / 4";
  EXPECT_EQ(rods[1].stiffness, 5) << "the branch's young is gone after ]";
  EXPECT_EQ(rods[1].load, Eigen::Vector3d(1, 0, 0));
  EXPECT_EQ(rods[1].loadAt, 0.25);
  EXPECT_EQ(rods[2].load, Eigen::Vector3d::Zero()) << "a load acts on one rod";
  EXPECT_EQ(solved.set->takeWarnings().size(), 0u);
}

TEST(PhysicsSet, BadArgumentsAreSkippedAndReportedWhereTheyHappen) {
  const auto solved = solveText("lsystem a { axiom rod(1, 0.1, 1) density(-1) rod(-2, 0.1, 1) load(0, 0, 0, 2) elastic(0.5) }\n", 0);
  EXPECT_EQ(solved.frame().rods.size(), 1u);
  const auto warnings = solved.set->takeWarnings();
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_EQ(warnings[0].count, 4u);
  EXPECT_EQ(warnings[0].span.line(), 1);
  EXPECT_EQ(warnings[0].span.column(), 34) << "at density(-1)";
}

TEST(PhysicsSet, ArrowsAreScaledAndColouredByMagnitude) {
  const auto solved = solveModel("statics_binary_tree.cell");
  draw(*solved.set);
  const auto& arrows = solved.set->arrows();
  ASSERT_EQ(arrows.size(), 30u) << "a force and a moment at each of the 15 joints";
  double largestForce = 0, largestMoment = 0, longest = 0;
  for (const RodResult& rod : solved.frame().rods) {
    largestForce = std::max(largestForce, rod.force.norm());
    largestMoment = std::max(largestMoment, rod.moment.norm());
    longest = std::max(longest, rod.length);
  }
  for (const DrawnArrow& arrow : arrows) {
    const double largest = arrow.heads == 1 ? largestForce : largestMoment;
    EXPECT_NEAR(glm::length(arrow.vector), longest * arrow.magnitude / largest, 1e-9) << "the largest is the longest rod";
    EXPECT_EQ(arrow.material, stressMaterial(arrow.magnitude / largest));
  }
  EXPECT_EQ(arrows[0].material, kPaletteSize - 1) << "the root's force is the largest: red";
  EXPECT_NEAR(arrows[0].vector.y, -longest, 1e-9) << "and points down";
  EXPECT_EQ(arrows[0].start, glm::dvec3(0.0)) << "from the root's base";
  ASSERT_EQ(arrows[16].heads, 2) << "the moments follow the forces";
  const Eigen::Vector3d& base = solved.frame().rods[1].base;
  EXPECT_EQ(arrows[16].start, glm::dvec3(base.x(), base.y(), base.z())) << "a moment starts at its joint";
  EXPECT_FALSE(solved.set->scene().geometry.empty());
  EXPECT_EQ(solved.set->scene().nodes.size(), 15u) << "a scene node per rod";
  EXPECT_EQ(solved.set->scene().nodes[1].parent, solved.frame().rods[0].id);

  const auto fixed = solveText("lsystem a { axiom arrows(0.5, -1) load(3, 0, 0) rod(1, 0.1, 0) }\n", 0);
  draw(*fixed.set);
  ASSERT_EQ(fixed.set->arrows().size(), 2u) << "the force and the external load; no moments";
  EXPECT_NEAR(fixed.set->arrows()[0].vector.x, 1.5, 1e-12) << "0.5 m per N";
  EXPECT_TRUE(fixed.set->arrows()[1].load);
  EXPECT_NEAR(fixed.set->arrows()[1].start.y, 1, 1e-12) << "a load is drawn from where it acts";
}

TEST(PhysicsSet, TheDeflectedShapeIsDrawnWhenTheModelIsElastic) {
  const auto bent = solveModel("cantilever.cell", {{"P", 2000}});
  const auto straight = solveModel("cantilever.cell", {{"P", 1e-9}});
  draw(*bent.set);
  draw(*straight.set);
  const double tipY = bent.frame().rods.back().tip.y();
  EXPECT_LT(tipY, -0.3);
  // The lowest point the rods themselves are drawn at (the nodes' triangles; arrows aside).
  auto lowestRod = [](const Scene& scene) {
    double lowest = INFINITY;
    const Mesh& mesh = scene.geometry.mesh();
    for (const SceneNode& node : scene.nodes)
      for (uint32_t t = node.range.firstTriangle; t < node.range.firstTriangle + node.range.triangleCount; ++t)
        for (uint32_t corner : mesh.triangles[t].position) lowest = std::min(lowest, mesh.positions[corner].y);
    return lowest;
  };
  EXPECT_NEAR(lowestRod(bent.set->scene()), tipY, 0.02) << "the rods are drawn bent down to the deflected tip";
  EXPECT_NEAR(lowestRod(straight.set->scene()), -0.01, 1e-6) << "at rest, down to their radius below the axis";
}

TEST(PhysicsSet, AFrameDependsOnlyOnItsWord) {
  const auto program = compileModel("statics_binary_tree.cell");
  World world(program);
  PhysicsSet followed;
  for (double t : {0.0, 1.0, 2.0, 3.0, 4.0}) {
    world.advanceTo(t, 1);
    followed.beginFrame(FrameTarget{".", "tree", 0, 1, t});
    interpretWord(world, followed);
    draw(followed);
  }
  const auto fresh = testing_support::solveProgram(program, 4.0);
  ASSERT_EQ(followed.frame().rods.size(), fresh.frame().rods.size());
  for (size_t i = 0; i < fresh.frame().rods.size(); ++i) {
    EXPECT_EQ(followed.frame().rods[i].id, fresh.frame().rods[i].id);
    EXPECT_EQ(followed.frame().rods[i].moment, fresh.frame().rods[i].moment);
  }
  EXPECT_EQ(followed.table().rows().at(followed.frame().rods[0].id).since, 1) << "the root appeared at t = 1";
  EXPECT_EQ(followed.table().rows().at(followed.frame().rods[14].id).since, 4);
}

// docs/LANGUAGE.md's section on the physics set says what each command of the table does,
// in the table's order (docs/COMMANDS.md, generated from the table, lists them).
TEST(PhysicsSet, TheLanguageReferenceListsTheCommandTable) {
  std::ifstream doc(std::string(ONTOGEN_SOURCE_DIR) + "/docs/LANGUAGE.md");
  std::string line;
  std::vector<std::string> documented;
  for (bool in = false; std::getline(doc, line);) {
    if (line.rfind("## ", 0) == 0 || line.rfind("### ", 0) == 0) in = line.find("The physics set") != std::string::npos;
    if (in && line.rfind("- `", 0) == 0) documented.push_back(line.substr(3, line.find('`', 3) - 3));
  }
  std::vector<std::string> table;
  for (const PhysicsCommand& command : physicsCommands()) table.emplace_back(command.signature);
  EXPECT_EQ(documented, table);
}

TEST(PhysicsSet, ARunDrawsRodsAndArrowsIntoEveryFrameOfOneGlb) {
  const fs::path dir = fs::path(ONTOGEN_BINARY_DIR) / "physics_set_test" / "run";
  fs::remove_all(dir);
  auto runOnce = [&](const fs::path& out) {
    RunDef def;
    def.program = compileModel("statics_binary_tree.cell");
    def.stem = "tree";
    def.frames = 5;
    def.sets = {"physics"};
    def.setOptions.formats = "glb,obj";
    def.out = out;
    ontogen::Run run(std::move(def));
    return run.execute();
  };
  const RunReport report = runOnce(dir / "a");
  ASSERT_TRUE(report.ok()) << (report.diagnostics.empty() ? "" : report.diagnostics[0].message);
  // Frame k (t = k) has 2^k - 1 rods, each with two arrows of a cylinder and cones.
  for (int frame = 1; frame < 5; ++frame) {
    char name[32];
    std::snprintf(name, sizeof name, "tree_%04d.obj", frame);
    std::ifstream obj(dir / "a" / name);
    std::string text((std::istreambuf_iterator<char>(obj)), std::istreambuf_iterator<char>());
    const size_t ramp = text.find("usemtl ontogen_" + std::to_string(kPaletteSize - 1));
    EXPECT_NE(ramp, std::string::npos) << name << " has the red arrow of its root";
  }
  runOnce(dir / "b");
  auto bytes = [](const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  };
  EXPECT_EQ(bytes(dir / "a" / "tree.glb"), bytes(dir / "b" / "tree.glb")) << "same program, same bytes";

  const fs::path modules = fs::path(ONTOGEN_SOURCE_DIR) / ".tools" / "node_modules";
  std::error_code missing;  // a .tools that does not resolve is a missing checker, not a crash
  REQUIRE_CHECKER(fs::exists(modules / "gltf-validator" / "package.json", missing), "the Khronos glTF validator");
  const fs::path script = fs::path(ONTOGEN_SOURCE_DIR) / "tests" / "interpreters" / "validate_gltf.js";
  auto [status, out] =
      runCommand("node '" + script.string() + "' '" + modules.string() + "' '" + (dir / "a" / "tree.glb").string() + "' 2>&1");
  EXPECT_EQ(status, 0) << out;
  EXPECT_NE(out.find("errors 0"), std::string::npos) << out;
}

}  // namespace
}  // namespace ontogen
