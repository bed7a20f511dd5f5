// Paper 000's leg (models/leg_gait.cell, Figs. 9 and 10 as printed), by value: the
// development functions of the joints, and the two known defects of the printed figures,
// pinned so that a change to the model or to the engine that hides them shows.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "core/word.h"
#include "core/world.h"
#include "tests/core/test_support.h"

namespace ontogen {
namespace {

constexpr double pi = std::numbers::pi;
constexpr double R_su = 0.056 * pi, A_su = 0.139 * pi, A_sw = 0.378 * pi, A_st = 0.056 * pi;

// The module of the leg with this label (or st2 for st) at time t.
struct Joint {
  std::string label;
  double n = 0, developed = 0, age = 0;
};
Joint jointAt(double t, const std::string& label) {
  World world(testing_support::compileModel("leg_gait.cell"), WorldDef{});
  world.advanceTo(t, 0.05);
  for (const WordCell& cell : captureWord(world))
    if (cell.label == label || (label == "st" && cell.label == "st2"))
      return {cell.label, cell.params[0], cell.developed[0], cell.age};
  ADD_FAILURE() << "no " << label << " at " << t;
  return {};
}

TEST(LegGait, TheSwingIsFig10sSineOverTheCycle) {
  // p1 makes the leg at t = 1 (β_ls = φ = 1); sw is born there with age 0 and lives φ.
  for (double tau : {0.1, 0.25, 0.4, 0.7, 0.9}) {
    const Joint sw = jointAt(1 + tau, "sw");
    EXPECT_NEAR(sw.age, tau, 1e-9);
    EXPECT_NEAR(sw.developed, A_sw * std::sin(2 * pi * tau), 1e-9) << tau;
  }
}

TEST(LegGait, TheTwistIsFig10sSineSquaredWhileStLives) {
  const Joint st = jointAt(1.1, "st");
  ASSERT_EQ(st.label, "st");
  EXPECT_NEAR(st.developed, A_st * std::pow(std::sin(pi * 0.1 / 0.2), 2), 1e-9);
}

TEST(LegGait, AsPrintedTheLiftJumpsByFortyDegreesHalfwayAndTenAtTheWrap) {
  // su is born at t = 1 with age 3 beta / 4: its tau reaches beta / 2 at t = 1.75.
  const Joint before = jointAt(1.74, "su"), after = jointAt(1.76, "su");
  EXPECT_NEAR(before.age, 0.49, 1e-9);
  EXPECT_DOUBLE_EQ(before.developed, 0);
  EXPECT_NEAR(after.developed, R_su - A_su * (std::cos(2 * pi * 0.01) + 1), 1e-9);
  EXPECT_NEAR((after.developed - before.developed) * 180 / pi, -40, 0.5) << "the jump at beta / 2";
  // And as the cycle wraps at t = 2.25: from about R_su back to 0.
  const Joint end = jointAt(2.24, "su"), start = jointAt(2.26, "su");
  EXPECT_NEAR(end.developed, R_su - A_su * (std::cos(2 * pi * 0.49) + 1), 1e-9);
  EXPECT_DOUBLE_EQ(start.developed, 0);
  EXPECT_NEAR((start.developed - end.developed) * 180 / pi, -10, 0.2) << "the jump at the wrap";
}

TEST(LegGait, AsPrintedTheTwistRepeatsEveryOnePointTwoCyclesNotEveryCycle) {
  // st (beta_st), st2 (2 beta_st), st(-n) (beta_st), st2 ...: a period of 6 beta_st = 1.2 phi.
  auto state = [](double t) {
    const Joint j = jointAt(t, "st");
    return j.label + (j.n > 0 ? "+" : "-");
  };
  bool differsAfterACycle = false;
  for (double t = 1.05; t < 2.2; t += 0.1) {
    EXPECT_EQ(state(t), state(t + 1.2)) << t;
    differsAfterACycle |= state(t) != state(t + 1.0);
  }
  EXPECT_TRUE(differsAfterACycle);
  EXPECT_EQ(state(1.1), "st+");
  EXPECT_EQ(state(1.3), "st2+");
  EXPECT_EQ(state(1.7), "st-");
}

}  // namespace
}  // namespace ontogen
