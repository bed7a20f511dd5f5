// Two-bone inverse kinematics against the law of cosines.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

#include "interpreters/creature/two_bone_ik.h"

namespace ontogen {
namespace {

TEST(TwoBoneIk, TheFootReachesTheTargetWithTheKneeTowardsThePole) {
  const glm::dvec3 hip(0, 2, 0), target(0.5, 0.2, 0.7), pole(0, 0, 1);
  const double upper = 1.2, lower = 1.1;
  const TwoBoneLeg leg = solveTwoBone(hip, target, upper, lower, pole);
  ASSERT_TRUE(leg.reached);
  const glm::dvec3 knee = hip + upper * leg.upperDirection;
  const glm::dvec3 foot = knee + lower * leg.lowerDirection;
  EXPECT_NEAR(glm::length(foot - target), 0, 1e-12);
  EXPECT_NEAR(glm::length(leg.upperDirection), 1, 1e-12);
  EXPECT_NEAR(glm::length(leg.lowerDirection), 1, 1e-12);
  // The knee lies off the hip-target line on the pole's side.
  const glm::dvec3 axis = glm::normalize(target - hip);
  const glm::dvec3 off = (knee - hip) - glm::dot(knee - hip, axis) * axis;
  EXPECT_GT(glm::dot(off, pole - glm::dot(pole, axis) * axis), 0);
  // Law of cosines: the knee's bend is pi minus the angle between the limbs.
  const double c = glm::length(target - hip);
  const double inner = std::acos((upper * upper + lower * lower - c * c) / (2 * upper * lower));
  EXPECT_NEAR(leg.kneeAngle, std::numbers::pi - inner, 1e-12);
  // The lower limb is the upper one turned away from the knee's side by the bend.
  const glm::dvec3 lower2 = std::cos(leg.kneeAngle) * leg.upperDirection - std::sin(leg.kneeAngle) * leg.kneeSide;
  EXPECT_NEAR(glm::length(lower2 - leg.lowerDirection), 0, 1e-12);
}

TEST(TwoBoneIk, ARightAngleKneeForEqualLimbsAtRootTwo) {
  const TwoBoneLeg leg = solveTwoBone({0, 0, 0}, {std::sqrt(2.0), 0, 0}, 1, 1, {0, 1, 0});
  EXPECT_NEAR(leg.kneeAngle, std::numbers::pi / 2, 1e-12);
  EXPECT_NEAR(leg.upperDirection.x, std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(leg.upperDirection.y, std::sqrt(0.5), 1e-12);
}

TEST(TwoBoneIk, ATargetOutOfReachStretchesTheLegTowardsIt) {
  const TwoBoneLeg leg = solveTwoBone({0, 0, 0}, {5, 0, 0}, 1, 1, {0, 1, 0});
  EXPECT_FALSE(leg.reached);
  EXPECT_NEAR(leg.kneeAngle, 0, 1e-3);
  EXPECT_NEAR(leg.upperDirection.x, 1, 1e-6);
  const TwoBoneLeg folded = solveTwoBone({0, 0, 0}, {0.1, 0, 0}, 1, 2, {0, 1, 0});
  EXPECT_FALSE(folded.reached) << "closer than the limbs' difference";
}

}  // namespace
}  // namespace ontogen
