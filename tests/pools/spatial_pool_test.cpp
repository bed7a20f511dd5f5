// The spatial pool's bucket index against a brute-force search.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <limits>
#include <random>
#include <vector>

#include "pools/spatial_pool.h"

namespace ontogen {
namespace {

TEST(SpatialPool, NeighboursMatchABruteForceSearch) {
  // Master 0 has state (x, y, z); master 1 only (y): x and z are 0 for it.
  SpatialPool pool(1.5, {{0, 1, 2}, {-1, 0, -1}});
  std::mt19937_64 random(3);
  std::uniform_real_distribution<double> coordinate(-6, 6);
  for (uint64_t id = 0; id < 600; ++id) {
    if (id % 5 == 0) {
      double y = coordinate(random);
      pool.append(CellRecord{1, 0, 0, id}, &y, 1);
    } else {
      double p[3] = {coordinate(random), coordinate(random), coordinate(random) * 0.3};
      pool.append(CellRecord{0, 0, 0, id}, p, 3);
    }
  }
  pool.index();
  std::vector<uint32_t> found;
  for (size_t i = 0; i < pool.size(); ++i) {
    pool.neighbours(i, found);
    std::vector<uint32_t> expected;
    const auto p = pool.positionOf(i);
    for (size_t j = 0; j < pool.size(); ++j) {
      if (j == i) continue;
      const auto q = pool.positionOf(j);
      const double d2 = (p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) + (p[2] - q[2]) * (p[2] - q[2]);
      if (d2 <= 1.5 * 1.5) expected.push_back(static_cast<uint32_t>(j));
    }
    std::sort(found.begin(), found.end());
    ASSERT_EQ(found, expected) << "cell " << i;
  }
}

// The table found in bucket order holds, row by row, what neighbours(i) gives, in its
// order: with dense buckets (cells filling their box) and hashed ones (a sparse scatter).
TEST(SpatialPool, TheNeighbourTableIsEveryCellsNeighbours) {
  for (const double spread : {8.0, 4000.0}) {
    SpatialPool pool(1.0, {{0, 1, -1}});
    std::mt19937_64 random(5);
    // Clusters 8 wide around 12 centres spread over `spread`: one box, or far apart.
    std::uniform_real_distribution<double> centre(0, spread), offset(0, 8);
    std::vector<std::array<double, 2>> centres(12);
    for (auto& c : centres) c = {centre(random), centre(random)};
    for (uint64_t id = 0; id < 3000; ++id) {
      const auto& c = centres[id % centres.size()];
      const double p[2] = {c[0] + offset(random), c[1] + offset(random)};
      pool.append(CellRecord{0, 0, 0, id}, p, 2);
    }
    pool.index();
    LargeVector<uint32_t> offsets, cells;
    std::vector<uint32_t> found;
    pool.neighbourTable(offsets, cells);
    ASSERT_EQ(offsets.size(), pool.size() + 1);
    size_t pairs = 0;
    for (size_t i = 0; i < pool.size(); ++i) {
      pool.neighbours(i, found);
      pairs += found.size();
      ASSERT_EQ(std::vector<uint32_t>(cells.begin() + offsets[i], cells.begin() + offsets[i + 1]), found)
          << "cell " << i << ", spread " << spread;
    }
    EXPECT_GT(pairs, pool.size()) << "spread " << spread << ": too few neighbours to tell";
  }
}

TEST(SpatialPool, FarAndNonFinitePositionsAreSafe) {
  SpatialPool pool(1, {{0, 1, -1}});
  const double far[2] = {1e300, 0}, nan[2] = {std::numeric_limits<double>::quiet_NaN(), 0}, near[2] = {0, 0.5},
               origin[2] = {0, 0};
  pool.append(CellRecord{0, 0, 0, 1}, far, 2);
  pool.append(CellRecord{0, 0, 0, 2}, nan, 2);
  pool.append(CellRecord{0, 0, 0, 3}, near, 2);
  pool.append(CellRecord{0, 0, 0, 4}, origin, 2);
  pool.index();
  std::vector<uint32_t> found;
  pool.neighbours(3, found);
  EXPECT_EQ(found, (std::vector<uint32_t>{2}));
  pool.neighbours(1, found);
  EXPECT_TRUE(found.empty()) << "NaN is no distance";
  pool.neighbours(0, found);
  EXPECT_TRUE(found.empty());
}

}  // namespace
}  // namespace ontogen
