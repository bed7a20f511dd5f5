// A model's state stays finite (core/finite_state.h): a rate or rule that makes it an
// infinity or NaN stops the development with an error at what writes it and the time,
// unless the program says #allow nonfinite.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "core/finite_state.h"
#include "core/world.h"
#include "tests/core/test_support.h"

namespace ontogen {
namespace {

using testing_support::compileOrFail;

struct Stopped {
  std::string message;
  int line = 0;
  int column = 0;
  double time = -1;
};

Stopped grow(const std::string& text, double until) {
  World world(compileOrFail(text));
  try {
    world.advanceTo(until, 1);
  } catch (const ModelError& error) {
    return {error.diagnostic.message, error.diagnostic.span.line(), error.diagnostic.span.column(), error.time};
  }
  return {};
}

TEST(FiniteState, FirstNonFiniteFindsInfinitiesAndNaNWhereverTheyStand) {
  std::vector<double> values(200, 1.5);
  EXPECT_EQ(firstNonFinite(values), 200u);
  values[130] = std::numeric_limits<double>::infinity();
  EXPECT_EQ(firstNonFinite(values), 130u);
  values[64] = -std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(firstNonFinite(values), 64u);
  values[0] = -std::numeric_limits<double>::infinity();
  EXPECT_EQ(firstNonFinite(values), 0u);
  values = {std::numeric_limits<double>::max(), std::numeric_limits<double>::denorm_min(), -0.0};
  EXPECT_EQ(firstNonFinite(values), 3u);
}

// x' = 100 x² from 1 blows up at t = 0.01; a Runge-Kutta step of 1 over the pole gives
// 4.8e25, the next an infinity.
TEST(FiniteState, ARateThatBlowsUpStopsAtTheRateWithTheTime) {
  const Stopped stopped = grow("cell A(x = 1) {\n  rules { rate(x) = x * x * 100; }\n}\n"
                               "system s { pool linear; axiom A; }\n",
                               5);
  EXPECT_EQ(stopped.line, 2);
  EXPECT_EQ(stopped.column, 11);
  EXPECT_EQ(stopped.time, 2);
  EXPECT_NE(stopped.message.find("'A' holds x = "), std::string::npos) << stopped.message;
  EXPECT_NE(stopped.message.find(" at t = 2, written by its rate: a model's state must stay finite (#allow nonfinite"),
            std::string::npos)
      << stopped.message;
}

TEST(FiniteState, AValueThatOverflowsStopsAtTheRuleThatMakesIt) {
  const Stopped successor = grow("cell A(x = 1) { rules { -> B(x * 1e200); } }\ncell B(y = 0) { rules { -> B(y * 1e200); } }\n"
                                 "system s { pool linear; axiom A; }\n",
                                 5);
  EXPECT_EQ(successor.message,
            "'B' holds y = inf at t = 2, written by a rule of 'B': a model's state must stay finite (#allow nonfinite "
            "accepts infinities and NaN)");
  EXPECT_EQ(successor.line, 2);
  EXPECT_EQ(successor.column, 28);
  const Stopped calculation = grow("cell A(x = 1) { rules { x = x * 1e300; } }\nsystem s { pool linear; axiom A; }\n", 5);
  EXPECT_EQ(calculation.time, 2);
  EXPECT_NE(calculation.message.find("'A' holds x = inf at t = 2, written by its calculation"), std::string::npos)
      << calculation.message;
  EXPECT_EQ(calculation.column, 25);
}

TEST(FiniteState, GridsAndNestedSystemsAreCheckedToo) {
  const Stopped grid = grow("cell U(u = 1) { rules { rate(u) = u * u * 100; } }\nsystem g { pool grid(4, 4); fill U(1); }\n", 3);
  EXPECT_EQ(grid.time, 2);
  EXPECT_NE(grid.message.find("written by its rate"), std::string::npos) << grid.message;
  const Stopped nested = grow("system top { pool linear; axiom inner; }\nsystem inner { pool linear; axiom A; }\n"
                              "cell A(x = 1) { rules { x = x * 1e300; } }\n",
                              5);
  EXPECT_EQ(nested.time, 2);
  EXPECT_NE(nested.message.find("'A' holds x = inf"), std::string::npos) << nested.message;
}

// A nested system that stops the development leaves every world whole: the run still
// counts their cells and bytes for its report (this read a null world, a segmentation
// fault in `ontogen run`).
TEST(FiniteState, AWorldStoppedByANestedSystemStillCountsEveryCell) {
  World world(compileOrFail("system top { pool linear; axiom inner inner; }\nsystem inner { pool linear; axiom A; }\n"
                            "cell A(x = 1) { rules { x = x * 1e300; } }\n"));
  EXPECT_THROW(world.advanceTo(5, 1), ModelError);
  EXPECT_EQ(world.totalCells(), 4u);  // two 'inner' cells, and the A of each
  EXPECT_EQ(world.held().cells, 4u);
}

// Every message of a run writes the values that are not finite as the language does,
// `inf`, `-inf` and `NaN`, never printf's `-nan` (the NaN x86 makes has its sign set).
TEST(FiniteState, MessagesWriteNaNAndInfinitiesAsTheLanguageDoes) {
  const Stopped nan = grow("cell A(x = -1) { rules { x = sqrt(x); } }\nsystem s { pool linear; axiom A; }\n", 5);
  EXPECT_EQ(nan.message,
            "'A' holds x = NaN at t = 1, written by its calculation: a model's state must stay finite (#allow nonfinite "
            "accepts infinities and NaN)");
  const Stopped negative = grow("cell A(x = -1) { rules { x = x * 1e300; } }\nsystem s { pool linear; axiom A; }\n", 5);
  EXPECT_NE(negative.message.find("'A' holds x = -inf at t = 2,"), std::string::npos) << negative.message;
  const Stopped age = grow("lsystem a {\n axiom A(-1)\n (B, 3) -> B\n A(x) -> (B, sqrt(x))\n}\n", 5);
  EXPECT_EQ(age.message, "'B' would be born with age NaN, but ages are ≥ 0 (in a rule of 'A' at t = 1)");
  const Stopped group = grow("lsystem a {\n axiom A\n use group: sqrt(time - 5)\n A -> A\n}\n", 5);
  EXPECT_EQ(group.message, "'use group' gives NaN at t = 0, not a whole number ≥ 0");
}

TEST(FiniteState, AProgramThatAllowsItDevelopsOn) {
  auto program = compileOrFail("#allow nonfinite\ncell A(x = 1) { rules { x = x * 1e300; } }\nsystem s { pool linear; axiom A; }\n");
  EXPECT_TRUE(program->allowsNonfinite);
  EXPECT_FALSE(checksFiniteState(*program));
  World world(program);
  world.advanceTo(5, 1);
  EXPECT_TRUE(std::isinf(world.rootPool().cellAt(0).state[0]));
  // A program without state has nothing to check.
  EXPECT_FALSE(checksFiniteState(*compileOrFail("lsystem a { axiom A\n A -> A A\n}\n")));
}

}  // namespace
}  // namespace ontogen
