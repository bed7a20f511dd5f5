// The environment channel (core/environment_process.h): a world asks its environment
// process after seeding and after every step, writes the answers into its query
// modules, and rules read them in the next step. Any environment can answer, not only
// the turtle: here one that reports the time and the module's place in the word.

#include <gtest/gtest.h>

#include "core/environment_process.h"
#include "core/world.h"
#include "interpreters/text/word_text.h"
#include "core/word.h"
#include "tests/core/test_support.h"

namespace ontogen {
namespace {

class Clock final : public EnvironmentProcess {
 public:
  void respond(const World& world, std::vector<QueryAnswer>& answers) const override {
    const auto cells = world.rootPool().cells();
    for (size_t i = 0; i < cells.size(); ++i)
      if (world.program().masters[cells[i].master].query != 0)
        answers.push_back({static_cast<uint32_t>(i), {world.time(), static_cast<double>(i), 7}});
  }
};

TEST(EnvironmentProcess, AnswersAfterSeedingAndEveryStepAndRulesReadThem) {
  auto program = testing_support::compileOrFail(
      "lsystem l {\n  axiom A ?P(0, 0, 0)\n  A > ?P(t, i, k) : t >= 2 -> B(t, i, k)\n  A -> A\n}");
  WorldDef def;
  def.environment = std::make_shared<const Clock>();
  World world(program, def);
  EXPECT_EQ(formatWord(captureWord(world)), "A ?P(0, 1, 7)") << "answered when seeded";
  world.advanceTo(2, 1);
  EXPECT_EQ(formatWord(captureWord(world)), "A ?P(2, 1, 7)") << "the rule read t = 1 in the step to 2";
  world.advanceTo(3, 1);
  EXPECT_EQ(formatWord(captureWord(world)), "B(2, 1, 7) ?P(3, 1, 7)");
}

TEST(EnvironmentProcess, WithoutAnEnvironmentQueriesKeepTheirValues) {
  auto program = testing_support::compileOrFail("lsystem l {\n  axiom F(2) ?P(1, 2, 3)\n}");
  World world(program);
  world.advanceTo(2, 1);
  EXPECT_EQ(formatWord(captureWord(world)), "F(2) ?P(1, 2, 3)");
}

}  // namespace
}  // namespace ontogen
