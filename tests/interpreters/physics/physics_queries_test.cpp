// Results back in the model: the query modules ?F, ?M and ?D read their rod's force,
// moment and deflection after every step, against closed forms, and growth that responds
// to load.

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "core/word.h"
#include "core/world.h"
#include "interpreters/physics/physics_queries.h"
#include "interpreters/physics/rigid_statics.h"
#include "interpreters/set_registry.h"
#include "tests/interpreters/physics/physics_support.h"

namespace ontogen {
namespace {

using testing_support::compileWithDefines;

World worldOf(const std::string& text) {
  std::shared_ptr<const Program> program = compileWithDefines(text, "queries.cell", {});
  WorldDef def;
  def.environment = queryEnvironmentOf(*program);
  EXPECT_NE(dynamic_cast<const PhysicsQueries*>(def.environment.get()), nullptr);
  return World(program, def);
}

// The parameters of the first cell labelled `label`.
std::vector<double> paramsOf(const World& world, const std::string& label) {
  for (const WordCell& cell : captureWord(world))
    if (cell.label == label) return cell.params;
  ADD_FAILURE() << "no " << label << " in the word";
  return {};
}

TEST(PhysicsQueries, AHorizontalRodReadsItsWeightAndTheMomentOfItsWeightAtItsMidpoint) {
  // 2 m, radius 0.1 m, 500 kg/m^3: m = 500 pi 0.01 2 = 10 pi kg; the turtle's ?H says
  // where the rod points, and the moment is (l/2) H x (-m g y).
  World world = worldOf(
      "lsystem beam {\n"
      "  axiom +(90) rod(2, 0.1, 500) ?F(9, 9, 9) ?M(9, 9, 9) ?D(9, 9, 9) ?H(9, 9, 9)\n"
      "}\n");
  const double m = 500 * std::numbers::pi * 0.01 * 2;
  const std::vector<double> f = paramsOf(world, "?F"), moment = paramsOf(world, "?M"), d = paramsOf(world, "?D"),
                            h = paramsOf(world, "?H");
  ASSERT_EQ(f.size(), 3u);
  ASSERT_EQ(h.size(), 3u);
  EXPECT_NEAR(f[0], 0, 1e-12);
  EXPECT_NEAR(f[1], -m * kGravity, 1e-9);
  EXPECT_NEAR(f[2], 0, 1e-12);
  EXPECT_NEAR(std::abs(h[0]), 1, 1e-12);  // horizontal
  // (l/2) h x (0, -w, 0) = (l/2) (h.z w, 0, -h.x w)
  const double w = m * kGravity;
  EXPECT_NEAR(moment[0], h[2] * w, 1e-9);
  EXPECT_NEAR(moment[1], 0, 1e-9);
  EXPECT_NEAR(moment[2], -h[0] * w, 1e-9);
  // Rigid: the tip has not moved.
  EXPECT_EQ(d, (std::vector<double>{0, 0, 0}));
}

TEST(PhysicsQueries, ACantileverReadsItsTipDeflectionUnderASmallLoad) {
  // Weightless, EI = 1000 N m^2, L = 2 m, P = 1 N at the tip: P L^3 / (3 EI).
  World world = worldOf(
      "lsystem cantilever {\n"
      "  axiom elastic(64) stiffness(1000) +(90) load(0, -1, 0) rod(2, 0, 0) ?D(0, 0, 0) ?F(0, 0, 0)\n"
      "}\n");
  const std::vector<double> d = paramsOf(world, "?D");
  ASSERT_EQ(d.size(), 3u);
  const double expected = 1.0 * 8 / (3 * 1000);
  EXPECT_NEAR(-d[1], expected, 0.01 * expected);
  EXPECT_NEAR(paramsOf(world, "?F")[1], -1, 1e-12);
}

TEST(PhysicsQueries, GrowthStopsWhereTheRootCarriesTheLoadItWasGivenAndTheAnswersFollowEachStep) {
  // Rods of mass 1 kg (r^2 = 1/pi m^2 at 1 kg/m^3, 1 m): the root carries 9.81 N a rod.
  // The apex adds a rod a step while its ?F, after the root rod, reads less than 45 N:
  // 1, 2, 3, 4 rods read less, 5 rods (49.05 N) stop it.
  const std::string radius = std::to_string(1 / std::sqrt(std::numbers::pi));  // as the program reads it
  const std::string rod = "rod(1, " + radius + ", 1)";
  World world = worldOf("lsystem stem {\n  axiom " + rod + " ?F(0, 0, 0) A\n  ignore: rod\n" +
                        "  ?F(x, y, z) < A : -y < 45 -> " + rod + " A\n}\n");
  auto rods = [&] {
    int count = 0;
    for (const WordCell& cell : captureWord(world)) count += cell.label == "rod";
    return count;
  };
  const double r = std::stod(radius);
  const double perRod = std::numbers::pi * r * r * kGravity;
  for (int step = 1; step <= 8; ++step) {
    world.advanceTo(step, 1);
    const int expected = std::min(step + 1, 5);
    EXPECT_EQ(rods(), expected) << "after step " << step;
    EXPECT_NEAR(paramsOf(world, "?F")[1], -perRod * expected, 1e-9) << "after step " << step;
  }
}

TEST(PhysicsQueries, AQueryWithNoRodBeforeItKeepsItsValues) {
  World world = worldOf("lsystem lone {\n  axiom ?F(1, 2, 3) rod(1, 0.1, 1)\n}\n");
  EXPECT_EQ(paramsOf(world, "?F"), (std::vector<double>{1, 2, 3}));
}

// models/statics_adaptive_tree.cell: rods thicken while their bending stress 4|M|/(pi r^3)
// is above STRESS; once grown, every rod bears it, and the loaded ones are thicker than
// the germ's schedule of radii (0.8 a generation) made them.
TEST(PhysicsQueries, TheAdaptiveTreeThickensUntilEveryRodBearsItsStress) {
  for (const double stress : {1e6, 4e6}) {
    std::shared_ptr<const Program> program =
        compileWithDefines(testing_support::readModel("statics_adaptive_tree.cell"), "models/statics_adaptive_tree.cell",
                           {{"STRESS", stress}});
    ASSERT_NE(program, nullptr);
    WorldDef def;
    def.environment = queryEnvironmentOf(*program);
    World world(program, def);
    world.advanceTo(program->until, program->dt);
    PhysicsSet set;
    FrameTarget target;
    target.time = world.time();
    set.beginFrame(target);
    interpretWord(world, set);
    const auto rods = set.table().rods();
    ASSERT_EQ(rods.size(), 31u);
    int thickened = 0;
    for (size_t i = 0; i < rods.size(); ++i) {
      const double r = rods[i].radius;
      const double sigma = 4 * set.frame().rods[i].moment.norm() / (std::numbers::pi * r * r * r);
      EXPECT_LE(sigma, stress) << "rod " << i << " at STRESS " << stress;
      // The schedule: 0.01 m at the root, 0.8 times a generation; the length says which.
      const double generation = std::round(std::log(rods[i].length()) / std::log(0.8));
      thickened += r > 0.01 * std::pow(0.8, generation) * 1.05;
    }
    EXPECT_GT(thickened, 0) << "STRESS " << stress;
  }
}

}  // namespace
}  // namespace ontogen
