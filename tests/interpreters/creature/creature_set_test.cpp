// The creature set's articulated turtle, driven command by command: forward kinematics
// through the joints, ranges held and counted, ids, sides and segments, and what each
// limb's triangles move with.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "interpreters/creature/creature_set.h"

namespace ontogen {
namespace {

constexpr double kDeg = std::numbers::pi / 180;

// Feeds a set cell by cell: each cell a list of commands.
struct Command {
  const char* name;
  std::vector<double> args;
};
void draw(CreatureSet& set, double time, const std::vector<std::vector<Command>>& cells) {
  set.beginFrame(FrameTarget{"/tmp", "test", 0, 1, time});
  set.beginWord(time);
  uint64_t id = 100;
  for (const auto& cell : cells) {
    set.beginCell(CellContext{id++, ~uint64_t{0}, 0, 1, time, ""});
    for (const Command& command : cell) set.execute(command.name, command.args);
  }
  set.endWord();
}

TEST(CreatureSet, ForwardKinematicsOfATwoLinkLegIsTheClosedForm) {
  CreatureSet set;
  const double a = 1.3, b = 0.7, t1 = 35, t2 = -80;
  // H starts along +x and U along +y: a hinge turns H towards U, in the x-y plane.
  draw(set, 0, {{{"hinge", {t1}}, {"limb", {a, 0.1}}}, {{"hinge", {t2}}, {"limb", {b, 0.1}}}, {{"foot", {}}}});
  const auto& joints = set.scene().skeleton.joints;
  ASSERT_EQ(joints.size(), 3u);
  const glm::dvec3 knee(a * std::cos(t1 * kDeg), a * std::sin(t1 * kDeg), 0);
  const glm::dvec3 foot = knee + b * glm::dvec3(std::cos((t1 + t2) * kDeg), std::sin((t1 + t2) * kDeg), 0);
  EXPECT_NEAR(glm::length(joints[0].position), 0, 1e-12);
  EXPECT_NEAR(glm::length(joints[1].position - knee), 0, 1e-12);
  EXPECT_NEAR(glm::length(joints[2].position - foot), 0, 1e-12);
  EXPECT_EQ(joints[1].parent, 0);
  EXPECT_EQ(joints[2].parent, 1);
  EXPECT_TRUE(joints[2].foot);
  // Each joint's frame composes its rotation with its parent's.
  EXPECT_NEAR(joints[1].orientation[0].x, std::cos((t1 + t2) * kDeg), 1e-12);
  EXPECT_NEAR(joints[1].orientation[0].y, std::sin((t1 + t2) * kDeg), 1e-12);
  EXPECT_NEAR(glm::determinant(joints[1].orientation), 1, 1e-12);
}

TEST(CreatureSet, AJointRangeHoldsTheDriverAndTheWarningCountsIt) {
  CreatureSet set;
  draw(set, 0, {{{"range", {0, -10, 10}}, {"hinge", {30}}, {"limb", {1, 0.1}}}, {{"hinge", {30}}, {"foot", {}}}});
  const auto& joints = set.scene().skeleton.joints;
  ASSERT_EQ(joints.size(), 3u);
  EXPECT_NEAR(joints[1].position.x, std::cos(10 * kDeg), 1e-12) << "held at 10 deg";
  EXPECT_NEAR(joints[1].position.y, std::sin(10 * kDeg), 1e-12);
  EXPECT_EQ(set.stats().clamped, 1u) << "the second hinge had no range";
  const auto warnings = set.takeWarnings();
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_EQ(warnings[0].count, 1u);
  EXPECT_NE(warnings[0].message.find("ranges"), std::string::npos);
}

TEST(CreatureSet, JointsTakeTheirCellsIdsAndLimbsMoveWithTheLastJoint) {
  CreatureSet set;
  draw(set, 0, {{{"hinge", {0}}, {"limb", {1, 0.2}}, {"hinge", {10}}}, {{"limb", {1, 0.2}}}, {{"limb", {1, 0}}}});
  const Scene& scene = set.scene();
  ASSERT_EQ(scene.skeleton.joints.size(), 2u);
  EXPECT_EQ(scene.skeleton.joints[0].id, 100u);
  EXPECT_NE(scene.skeleton.joints[1].id, 100u) << "a cell's second joint gets an id of its own";
  ASSERT_EQ(scene.skeleton.skin.size(), 2u) << "the line limb has no triangles";
  EXPECT_EQ(scene.skeleton.skin[0].joint, 0);
  EXPECT_EQ(scene.skeleton.skin[1].joint, 1) << "the second cell's limb hangs from the joint before it";
  EXPECT_EQ(scene.skeleton.skin[0].firstTriangle + scene.skeleton.skin[0].triangleCount,
            scene.skeleton.skin[1].firstTriangle);
  EXPECT_EQ(scene.geometry.segmentCount(), 1u);
}

TEST(CreatureSet, ALegStandsOnItsFootholdWithItsKneeUp) {
  CreatureSet set;
  // A creature with one leg to its left: out along the creature's left, then solved.
  const std::vector<std::vector<Command>> word = {
      {{"gait", {1, 0.5, 0.4, 0.2, 0.8}}},
      {{"[", {}}, {"+", {90}}, {"hip", {0, 0.9, 1.0, 1.1, 0}}},
      {{"limb", {0.9, 0.1}}, {"knee", {}}, {"limb", {1.0, 0.1}}, {"foot", {}}, {"]", {}}}};
  draw(set, 0.1, word);  // in stance: touchdown at 0, down until 0.5
  const auto& joints = set.scene().skeleton.joints;
  ASSERT_EQ(joints.size(), 4u);
  const double speed = 0.4 / 0.5;
  EXPECT_NEAR(joints[0].position.x, speed * 0.1, 1e-12) << "the root travels at the stance feet's push";
  EXPECT_NEAR(joints[0].position.y, 0.8, 1e-12);
  const glm::dvec3 foot = joints[3].position;
  // Touched down at t = 0 half a stride ahead of the neutral point (0, 0, -1.1).
  EXPECT_NEAR(foot.x, 0.2, 1e-9);
  EXPECT_NEAR(foot.y, 0, 1e-9);
  EXPECT_NEAR(foot.z, -1.1, 1e-9);
  EXPECT_GT(joints[2].position.y, 0.8) << "the knee is above the hip: towards the hip's U";
  EXPECT_EQ(joints[1].side, BodySide::Left);
  EXPECT_EQ(set.stats().unreached, 0u);
  // Later in the stance the foot has not moved.
  draw(set, 0.45, word);
  EXPECT_NEAR(glm::length(set.scene().skeleton.joints[3].position - foot), 0, 1e-9);
}

TEST(CreatureSet, BadArgumentsAreIgnoredAndCounted) {
  CreatureSet set;
  draw(set, 0, {{{"gait", {1, 1.5, 1, 1, 1}}, {"limb", {-1, 0.1}}, {"knee", {}}, {"]", {}}, {"hinge", {NAN}}}});
  EXPECT_TRUE(set.scene().skeleton.empty());
  const auto warnings = set.takeWarnings();
  // The gait out of range is named apart, with its reason.
  ASSERT_EQ(warnings.size(), 2u);
  EXPECT_EQ(warnings[0].count, 4u);
  EXPECT_NE(warnings[0].message.find("bad arguments"), std::string::npos);
  EXPECT_EQ(warnings[1].count, 1u);
  EXPECT_EQ(warnings[1].message, "the creature set made no creature of 1 gait out of range: the duty factor must be "
                                 "between 0 and 1 (the first here)");
}

// Finite arguments that would place a joint, a foot or a limb beyond what outputs hold
// (past ±1e30, or overflowing to infinity) are undone and counted: nothing non-finite
// reaches the joints' tracks or the glTF.
TEST(CreatureSet, CommandsThatWouldPlaceBeyondTheOutputsAreUndoneAndCounted) {
  CreatureSet set;
  draw(set, 10,
       {{{"f", {1e29}}, {"f", {1e308}}, {"bend", {0, 0}}, {"limb", {1e308, 0.1}}, {"limb", {1, 0.1}},
         {"gait", {1, 0.5, 1e300, 0.1, 1}}, {"hip", {0, 1, 1, 1, 0}}, {"knee", {}}, {"foot", {}}}});
  const auto& joints = set.scene().skeleton.joints;
  ASSERT_FALSE(joints.empty());
  for (const SceneJoint& joint : joints)
    for (int i = 0; i < 3; ++i) {
      EXPECT_LE(std::abs(joint.position[i]), 1e30) << joint.name;
      for (int j = 0; j < 3; ++j) EXPECT_TRUE(std::isfinite(joint.orientation[i][j])) << joint.name;
    }
  EXPECT_EQ(joints[0].position.x, 1e29) << "the first move fits; the second goes past 1e30";
  const auto warnings = set.takeWarnings();
  ASSERT_FALSE(warnings.empty());
  EXPECT_NE(warnings[0].message.find("bad arguments"), std::string::npos);
}

}  // namespace
}  // namespace ontogen
