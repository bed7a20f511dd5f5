// The rigid statics (Eq. 1, Eq. 2) by value against closed forms, on the paper's models
// and on small trees: the root carries minus g times the mass plus the external forces,
// a symmetric tree no root moment, every rod the moment of all the loads above it about
// its base, and a tree cut into more rods the same root force and moment.

#include "interpreters/physics/rigid_statics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <unordered_map>

#include <Eigen/Geometry>

#include "tests/interpreters/physics/physics_support.h"

namespace ontogen {
namespace {

using testing_support::solveModel;
using testing_support::solveText;

// Is rod `above` rod `below` or in the subtree it carries?
bool carries(const PhysicsFrame& frame, size_t below, size_t above) {
  std::unordered_map<uint64_t, size_t> index;
  for (size_t i = 0; i < frame.rods.size(); ++i) index[frame.rods[i].id] = i;
  for (size_t at = above;;) {
    if (at == below) return true;
    const uint64_t parent = frame.rods[at].parent;
    if (parent == kNoParentRod) return false;
    at = index.at(parent);
  }
}

double scaleOf(const Eigen::Vector3d& v) { return std::max(1.0, v.norm()); }

TEST(RigidStatics, TheBinaryTreeOfThePaperWeighsWhatItsRodsDo) {
  const auto solved = solveModel("statics_binary_tree.cell");
  const PhysicsFrame& frame = solved.frame();
  ASSERT_EQ(frame.rods.size(), 15u);
  // Rods of 5 m, 0.8 as long in each of 4 generations of 1, 2, 4, 8, radius 1, density 1.
  double length = 0;
  for (int k = 0; k < 4; ++k) length += std::pow(2.0, k) * 5 * std::pow(0.8, k);
  const double mass = std::numbers::pi * length;
  const RodResult& root = frame.rods[0];
  EXPECT_EQ(root.parent, kNoParentRod);
  EXPECT_NEAR(root.force.y(), -kGravity * mass, 1e-9 * kGravity * mass);
  EXPECT_NEAR(root.force.x(), 0, 1e-9);
  EXPECT_NEAR(root.force.z(), 0, 1e-9);
  EXPECT_LT(root.moment.norm(), 1e-9 * kGravity * mass * 5) << "the tree is symmetric about its root's axis";
  EXPECT_GT(frame.rods[1].moment.norm(), 10.0) << "a branch leans, so it carries a moment";
}

TEST(RigidStatics, EveryRootCarriesMinusGTimesItsMassPlusTheExternalForces) {
  for (const char* model : {"statics_binary_tree.cell", "statics_spiral.cell", "statics_quad_tree.cell"}) {
    SCOPED_TRACE(model);
    const auto solved = solveModel(model);
    const PhysicsFrame& frame = solved.frame();
    ASSERT_FALSE(frame.rods.empty());
    double mass = 0;
    Eigen::Vector3d external = Eigen::Vector3d::Zero();
    for (const RodResult& rod : frame.rods) {
      mass += rod.mass;
      external += rod.load;
    }
    const Eigen::Vector3d expected = -kGravity * mass * kWorldUp + external;
    int roots = 0;
    for (const RodResult& rod : frame.rods) {
      if (rod.parent != kNoParentRod) continue;
      ++roots;
      EXPECT_LT((rod.force - expected).norm(), 1e-10 * scaleOf(expected)) << rod.force.transpose();
    }
    EXPECT_EQ(roots, 1);
  }
  const auto quad = solveModel("statics_quad_tree.cell", {{"WIND", 20}});
  EXPECT_EQ(quad.frame().rods.size(), 21u);
  EXPECT_NEAR(quad.frame().rods[0].force.x(), 21 * 20, 1e-9) << "21 rods, 20 N of wind each";
  EXPECT_EQ(solveModel("statics_spiral.cell").frame().rods.size(), 29u);
}

TEST(RigidStatics, ASymmetricQuadTreeHasNoRootMomentAndWindGivesOne) {
  const auto calm = solveModel("statics_quad_tree.cell", {{"WIND", 0}});
  const RodResult& root = calm.frame().rods[0];
  EXPECT_LT(root.moment.norm(), 1e-9 * root.force.norm());
  const auto windy = solveModel("statics_quad_tree.cell", {{"WIND", 20}});
  EXPECT_GT(windy.frame().rods[0].moment.norm(), 100.0);
}

// M_i = sum over the rods k that rod i carries (itself too) of (weight point - P_i) x
// weight + (load point - P_i) x load: the moment about a base of all the loads above it.
TEST(RigidStatics, EveryMomentIsTheSumOfTheLoadsAboveItsBaseTimesTheirLevers) {
  for (const char* model : {"statics_binary_tree.cell", "statics_spiral.cell", "statics_quad_tree.cell"}) {
    SCOPED_TRACE(model);
    const auto solved = solveModel(model);
    const PhysicsFrame& frame = solved.frame();
    for (size_t i = 0; i < frame.rods.size(); ++i) {
      const RodResult& rod = frame.rods[i];
      Eigen::Vector3d moment = Eigen::Vector3d::Zero(), force = Eigen::Vector3d::Zero();
      for (size_t k = 0; k < frame.rods.size(); ++k) {
        if (!carries(frame, i, k)) continue;
        const RodResult& above = frame.rods[k];
        const Eigen::Vector3d weight = -kGravity * above.mass * kWorldUp;
        moment += (0.5 * (above.base + above.restTip) - rod.base).cross(weight) +
                  (above.loadPoint - rod.base).cross(above.load);
        force += weight + above.load;
      }
      EXPECT_LT((rod.moment - moment).norm(), 1e-9 * scaleOf(moment)) << "rod " << i;
      EXPECT_LT((rod.force - force).norm(), 1e-9 * scaleOf(force)) << "rod " << i;
    }
  }
}

TEST(RigidStatics, ATreeCutIntoMoreRodsHasTheSameRootForceAndMoment) {
  const auto whole = solveText(
      "lsystem a { axiom rod(2, 0.1, 5) [ +(30) load(1, 2, 3, 0.5) rod(1, 0.1, 5) ] &(20) rod(1.5, 0.2, 7) }\n", 0);
  const auto cut = solveText(
      "lsystem a { axiom rod(1, 0.1, 5) rod(1, 0.1, 5) [ +(30) load(1, 2, 3, 1) rod(0.5, 0.1, 5) rod(0.5, 0.1, 5) ]"
      " &(20) rod(0.5, 0.2, 7) rod(0.5, 0.2, 7) rod(0.5, 0.2, 7) }\n",
      0);
  ASSERT_EQ(whole.frame().rods.size(), 3u);
  ASSERT_EQ(cut.frame().rods.size(), 7u);
  const RodResult& a = whole.frame().rods[0];
  const RodResult& b = cut.frame().rods[0];
  EXPECT_LT((a.force - b.force).norm(), 1e-12 * a.force.norm());
  EXPECT_LT((a.moment - b.moment).norm(), 1e-12 * a.moment.norm()) << a.moment.transpose() << " / " << b.moment.transpose();
  EXPECT_GT(a.moment.norm(), 1.0);
}

TEST(RigidStatics, TheCantileversRootCarriesTheTipLoadTimesItsLength) {
  const auto solved = solveModel("cantilever.cell", {{"L", 2}, {"P", 3}});
  const RodTable& table = solved.set->table();
  const std::vector<RodLoads> loads = solveRigidStatics(table.rods(), table.leavesFirst());
  ASSERT_EQ(loads.size(), 10u);
  EXPECT_NEAR(loads[0].force.y(), -3, 1e-12) << "weightless";
  EXPECT_NEAR(loads[0].moment.z(), -3 * 2, 1e-12);
  EXPECT_NEAR(loads[5].moment.z(), -3 * 2 * 0.5, 1e-12) << "half way along, half the lever";
  EXPECT_NEAR(loads[0].moment.x(), 0, 1e-12);
  EXPECT_NEAR(loads[0].moment.y(), 0, 1e-12);
}

}  // namespace
}  // namespace ontogen
