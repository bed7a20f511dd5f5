// The relationship and design-model tables: the sweep order from the relationship graph,
// parents by id, rows kept across frames and dropped when their rod is gone.

#include "interpreters/physics/rod_table.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

namespace ontogen {
namespace {

Rod rodOf(uint64_t id, uint64_t parent) {
  Rod rod;
  rod.id = id;
  rod.parent = parent;
  rod.tip = Eigen::Vector3d(0, 1, 0);
  return rod;
}

TEST(RodTable, TheSweepVisitsEveryRodAfterAllOfItsChildren) {
  // 0 <- 1 <- 3, 0 <- 2, 1 <- 4, 2 <- 5 <- 6
  const std::vector<int> parents = {-1, 0, 0, 1, 1, 2, 5};
  const std::vector<int> order = leavesFirstOrder(parents);
  ASSERT_EQ(order.size(), parents.size());
  std::vector<int> position(parents.size(), -1);
  for (size_t k = 0; k < order.size(); ++k) position[static_cast<size_t>(order[k])] = static_cast<int>(k);
  for (size_t child = 0; child < parents.size(); ++child) {
    EXPECT_GE(position[child], 0) << child << " is visited";
    if (parents[child] >= 0) {
      EXPECT_LT(position[child], position[static_cast<size_t>(parents[child])]) << child;
    }
  }
}

// Rods are drawn parents first: the sweep is then the drawing order reversed, which walks
// memory in order; a parent drawn after its child is still swept after it.
TEST(RodTable, TheSweepOfRodsDrawnParentsFirstIsTheirOrderReversed) {
  EXPECT_EQ(leavesFirstOrder(std::vector<int>{-1, 0, 1, 1, 0, 4, 4}), (std::vector<int>{6, 5, 4, 3, 2, 1, 0}));
  const std::vector<int> order = leavesFirstOrder(std::vector<int>{2, -1, 1});
  ASSERT_EQ(order.size(), 3u);
  const auto at = [&](int rod) { return std::find(order.begin(), order.end(), rod) - order.begin(); };
  EXPECT_LT(at(0), at(2));
  EXPECT_LT(at(2), at(1));
}

TEST(RodTable, ParentsAreFoundByIdAndAnUnknownParentMakesARoot) {
  RodTable table;
  table.beginFrame(0);
  table.add(rodOf(10, kNoParentRod));
  table.add(rodOf(11, 10));
  table.add(rodOf(12, 10));
  table.add(rodOf(13, 99));  // its parent drew no rod
  table.finish();
  const auto rods = table.rods();
  EXPECT_EQ(rods[1].parentIndex, 0);
  EXPECT_EQ(rods[2].parentIndex, 0);
  EXPECT_EQ(rods[3].parentIndex, -1);
  EXPECT_EQ(rods[3].parent, kNoParentRod);
  ASSERT_EQ(table.children(0).size(), 2u);
  EXPECT_EQ(table.children(0)[0], 1);
  EXPECT_EQ(table.children(0)[1], 2);
  EXPECT_TRUE(table.children(3).empty());
}

TEST(RodTable, RowsLastWhileTheirRodsDoAndGoWithThem) {
  RodTable table;
  table.beginFrame(1);
  table.add(rodOf(10, kNoParentRod));
  table.add(rodOf(11, 10));
  table.finish();
  table.beginFrame(2);
  table.add(rodOf(10, kNoParentRod));
  table.add(rodOf(12, 10));
  table.finish();
  ASSERT_EQ(table.rows().size(), 2u);
  EXPECT_EQ(table.rows().at(10).since, 1) << "a rod keeps the time it first appeared";
  EXPECT_EQ(table.rows().at(12).since, 2);
  EXPECT_EQ(table.rows().at(12).parent, 10u);
  EXPECT_EQ(table.rows().at(12).index, 1);
  EXPECT_EQ(table.rows().count(11), 0u) << "a rod that is gone loses its row";
}

}  // namespace
}  // namespace ontogen
