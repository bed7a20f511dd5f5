// The gait in closed form (interpreters/creature/gait.h): phases, footholds, the swing's
// arc and the body's speed, against values worked out by hand.

#include <gtest/gtest.h>

#include <cmath>

#include <glm/geometric.hpp>

#include "interpreters/creature/gait.h"

namespace ontogen {
namespace {

const GaitDef kGait{.period = 2, .duty = 0.6, .stride = 0.9, .lift = 0.25, .height = 1};
const glm::dvec3 kForward(1, 0, 0), kUp(0, 1, 0);

TEST(Gait, SpeedIsWhatAStanceFootPushes) {
  EXPECT_DOUBLE_EQ(kGait.speed(), 0.9 / (0.6 * 2));
  EXPECT_EQ(gaitError(kGait), nullptr);
  EXPECT_NE(gaitError({.period = 1, .duty = 1, .stride = 1, .lift = 0, .height = 1}), nullptr);
  EXPECT_NE(gaitError({.period = 0, .duty = 0.5, .stride = 1, .lift = 0, .height = 1}), nullptr);
  EXPECT_NE(gaitError({.period = 1, .duty = 0.5, .stride = NAN, .lift = 0, .height = 1}), nullptr);
}

TEST(Gait, AFootIsDownForTheDutyFactorOfEachCycleFromItsPhase) {
  // Touchdowns at (k + 0.25) * 2 = 0.5, 2.5, ...; down for 1.2 s of each 2.
  EXPECT_FALSE(footPhase(kGait, 0.25, 0.49).stance);
  EXPECT_TRUE(footPhase(kGait, 0.25, 0.5).stance);
  EXPECT_TRUE(footPhase(kGait, 0.25, 1.69).stance);
  EXPECT_FALSE(footPhase(kGait, 0.25, 1.71).stance);
  EXPECT_DOUBLE_EQ(footPhase(kGait, 0.25, 1.0).touchdown, 0.5);
  EXPECT_DOUBLE_EQ(footPhase(kGait, 0.25, 2.0).touchdown, 0.5) << "in swing: the stance before";
  EXPECT_NEAR(footPhase(kGait, 0.25, 2.1).swing, (2.1 - 1.7) / 0.8, 1e-12);
  EXPECT_DOUBLE_EQ(footPhase(kGait, 1.25, 1.0).touchdown, 0.5) << "phases are cycles: 1.25 is 0.25";
  // Samples of the whole cycle: the fraction on the ground is the duty factor.
  int down = 0;
  const int samples = 20000;
  for (int i = 0; i < samples; ++i) down += footPhase(kGait, 0.4, 2.0 * i / samples).stance;
  EXPECT_NEAR(static_cast<double>(down) / samples, 0.6, 1.0 / samples);
}

TEST(Gait, AStanceFootStaysWhereItTouchedDownHalfAStrideAhead) {
  // The neutral point moves with the body: n(t) = (speed * t, 0, 0).
  auto neutral = [](double t) { return glm::dvec3(kGait.speed() * t, 0, -1); };
  const glm::dvec3 planted = footPosition(kGait, 0.25, kGait.lift, 0.5, neutral(0.5), kForward, kUp);
  EXPECT_NEAR(planted.x, neutral(0.5).x + 0.45, 1e-12);
  for (double t = 0.5; t < 1.7; t += 0.01) {
    const glm::dvec3 at = footPosition(kGait, 0.25, kGait.lift, t, neutral(t), kForward, kUp);
    EXPECT_NEAR(glm::length(at - planted), 0, 1e-12) << t;
  }
  // At lift-off it is half a stride behind the neutral point.
  EXPECT_NEAR(planted.x - neutral(1.7).x, -0.45, 1e-12);
}

TEST(Gait, ASwingRisesToTheLiftAndLandsOnTheNextFootholdAtRest) {
  auto neutral = [](double t) { return glm::dvec3(kGait.speed() * t, 0, 0); };
  auto at = [&](double t) { return footPosition(kGait, 0.25, kGait.lift, t, neutral(t), kForward, kUp); };
  const glm::dvec3 liftOff = at(1.7 - 1e-9), touchdown = at(2.5);
  EXPECT_NEAR(touchdown.x - liftOff.x, kGait.speed() * kGait.period, 1e-6) << "a step is speed * period";
  EXPECT_NEAR(at(2.1).y, kGait.lift, 1e-12) << "the highest point halfway";
  glm::dvec3 previous = at(1.7);
  double highest = 0;
  for (double t = 1.7; t <= 2.5 + 1e-12; t += 0.001) {
    const glm::dvec3 p = at(t);
    EXPECT_GE(p.y, -1e-15) << "never below the ground";
    EXPECT_LT(glm::length(p - previous), 0.01) << "continuous, at " << t;
    highest = std::max(highest, p.y);
    previous = p;
  }
  EXPECT_NEAR(highest, kGait.lift, 1e-6);
  // At rest where the swing ends: progress and height have zero slope there.
  EXPECT_NEAR(swingProgress(1e-4), 0, 1e-10);
  EXPECT_NEAR(1 - swingProgress(1 - 1e-4), 0, 1e-10);
  EXPECT_NEAR(swingHeight(1e-4), 0, 1e-6);
  EXPECT_DOUBLE_EQ(swingProgress(0.5), 0.5);
}

}  // namespace
}  // namespace ontogen
