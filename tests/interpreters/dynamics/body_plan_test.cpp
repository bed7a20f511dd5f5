#include "interpreters/dynamics/body_plan.h"

#include <gtest/gtest.h>

#include <cmath>

namespace ontogen {
namespace {

// A base frame that is no axis frame, so every axis and sign is exercised.
glm::dmat3 tilted() {
  const std::array<double, 3> angles{0.3, -0.7, 1.1};
  return turned(JointKind::Hip, glm::dmat3(1.0), angles);
}

TEST(BodyPlan, AnglesTurnTheBaseIntoTheOrientationAndBack) {
  const glm::dmat3 base = tilted();
  const struct {
    JointKind kind;
    std::array<double, 3> angles;
  } cases[] = {{JointKind::Bend, {0.25, -0.1, 0}},
               {JointKind::Hinge, {-0.6, 0, 0}},
               {JointKind::Knee, {1.9, 0, 0}},
               {JointKind::Hip, {-0.8, 0.5, 0.3}}};
  for (const auto& c : cases) {
    const glm::dmat3 orientation = turned(c.kind, base, c.angles);
    const std::array<double, 3> found = hingeAngles(c.kind, base, orientation);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(found[i], c.angles[i], 1e-12) << static_cast<int>(c.kind) << " " << i;
  }
}

// The creature set's turns: bend's yaw takes H towards L, its pitch H towards U; a
// hinge's angle H towards U; a knee's H away from U.
TEST(BodyPlan, HingesTurnAsTheCreatureSetTurns) {
  const glm::dmat3 id(1.0);
  const double a = 0.4;
  const glm::dmat3 yawed = turned(JointKind::Bend, id, {a, 0, 0});
  EXPECT_NEAR(yawed[0].y, std::sin(a), 1e-15);
  const glm::dmat3 pitched = turned(JointKind::Bend, id, {0, a, 0});
  EXPECT_NEAR(pitched[0].z, std::sin(a), 1e-15);
  EXPECT_NEAR(turned(JointKind::Hinge, id, {a, 0, 0})[0].z, std::sin(a), 1e-15);
  EXPECT_NEAR(turned(JointKind::Knee, id, {a, 0, 0})[0].z, -std::sin(a), 1e-15);
  EXPECT_EQ(hingeCount(JointKind::Free), 0);
  EXPECT_EQ(hingeCount(JointKind::Weld), 0);
  EXPECT_EQ(hingeCount(JointKind::Hip), 3);
}

}  // namespace
}  // namespace ontogen
