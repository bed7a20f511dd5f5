// Grid sites, neighbourhoods and boundaries, at edges and corners.

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "pools/grid_pool.h"

namespace ontogen {
namespace {

GridShape shape2(uint32_t nx, uint32_t ny, GridBoundary boundary, GridNeighbourhood neighbourhood) {
  GridShape shape;
  shape.dimensions = 2;
  shape.size = {nx, ny, 1};
  shape.boundary = boundary;
  shape.neighbourhood = neighbourhood;
  return shape;
}

std::vector<uint32_t> neighbours(const GridPool& grid, GridCoordinates at) {
  uint32_t out[GridPool::kMaxNeighbours];
  int n = grid.neighbourSites(grid.siteAt(at), out);
  return {out, out + n};
}

TEST(GridPool, SitesAndCoordinatesRoundTrip) {
  GridShape shape;
  shape.dimensions = 3;
  shape.size = {4, 3, 2};
  GridPool grid(shape);
  EXPECT_EQ(grid.siteCount(), 24u);
  for (uint32_t site = 0; site < 24; ++site) EXPECT_EQ(grid.siteAt(grid.coordinates(site)), site);
  EXPECT_EQ(grid.siteAt({1, 2, 1}), 1u + 4u * (2u + 3u * 1u));
}

TEST(GridPool, NeighbourhoodSizes) {
  EXPECT_EQ(GridPool(shape2(5, 5, GridBoundary::Wrap, GridNeighbourhood::VonNeumann)).offsets().size(), 4u);
  EXPECT_EQ(GridPool(shape2(5, 5, GridBoundary::Wrap, GridNeighbourhood::Moore)).offsets().size(), 8u);
  GridShape cube;
  cube.dimensions = 3;
  cube.size = {3, 3, 3};
  cube.neighbourhood = GridNeighbourhood::Moore;
  EXPECT_EQ(GridPool(cube).offsets().size(), 26u);
  cube.neighbourhood = GridNeighbourhood::VonNeumann;
  EXPECT_EQ(GridPool(cube).offsets().size(), 6u);
  GridShape line;
  line.size = {7, 1, 1};
  EXPECT_EQ(GridPool(line).offsets().size(), 2u);
}

TEST(GridPool, VonNeumannOrderIsNorthWestEastSouth) {
  GridPool grid(shape2(5, 4, GridBoundary::Closed, GridNeighbourhood::VonNeumann));
  // (2, 1): offsets (0,-1) (-1,0) (1,0) (0,1).
  EXPECT_EQ(neighbours(grid, {2, 1, 0}), (std::vector<uint32_t>{grid.siteAt({2, 0, 0}), grid.siteAt({1, 1, 0}),
                                                                grid.siteAt({3, 1, 0}), grid.siteAt({2, 2, 0})}));
}

TEST(GridPool, ClosedCornerHasNoNeighboursOutside) {
  GridPool grid(shape2(5, 4, GridBoundary::Closed, GridNeighbourhood::Moore));
  auto corner = neighbours(grid, {0, 0, 0});
  EXPECT_EQ(std::count(corner.begin(), corner.end(), GridPool::kEmpty), 5);
  auto edge = neighbours(grid, {2, 3, 0});
  EXPECT_EQ(std::count(edge.begin(), edge.end(), GridPool::kEmpty), 3);
  auto inside = neighbours(grid, {2, 2, 0});
  EXPECT_EQ(std::count(inside.begin(), inside.end(), GridPool::kEmpty), 0);
}

TEST(GridPool, WrapCornerReachesTheOppositeCorners) {
  GridPool grid(shape2(5, 4, GridBoundary::Wrap, GridNeighbourhood::Moore));
  auto corner = neighbours(grid, {0, 0, 0});
  ASSERT_EQ(corner.size(), 8u);
  EXPECT_EQ(corner[0], grid.siteAt({4, 3, 0}));  // (-1, -1)
  EXPECT_EQ(corner[1], grid.siteAt({0, 3, 0}));  // (0, -1)
  EXPECT_EQ(corner[2], grid.siteAt({1, 3, 0}));  // (1, -1)
  EXPECT_EQ(corner[3], grid.siteAt({4, 0, 0}));  // (-1, 0)
  EXPECT_EQ(corner[7], grid.siteAt({1, 1, 0}));  // (1, 1)
  std::vector<uint32_t> sorted = corner;
  std::sort(sorted.begin(), sorted.end());
  EXPECT_EQ(std::unique(sorted.begin(), sorted.end()), sorted.end()) << "8 distinct sites";
}

TEST(GridPool, ClampRepeatsTheEdgeSite) {
  GridPool grid(shape2(5, 4, GridBoundary::Clamp, GridNeighbourhood::VonNeumann));
  auto corner = neighbours(grid, {4, 3, 0});
  const uint32_t self = grid.siteAt({4, 3, 0});
  EXPECT_EQ(corner, (std::vector<uint32_t>{grid.siteAt({4, 2, 0}), grid.siteAt({3, 3, 0}), self, self}));
}

TEST(GridPool, OneDimensionalWrap) {
  GridShape line;
  line.size = {6, 1, 1};
  line.boundary = GridBoundary::Wrap;
  GridPool grid(line);
  EXPECT_EQ(neighbours(grid, {0, 0, 0}), (std::vector<uint32_t>{5, 1}));
  EXPECT_EQ(neighbours(grid, {5, 0, 0}), (std::vector<uint32_t>{4, 0}));
}

TEST(GridPool, PlacementKeepsSiteOrder) {
  GridPool grid(shape2(3, 3, GridBoundary::Closed, GridNeighbourhood::Moore));
  const double a = 1, b = 2, c = 3;
  grid.place(7, CellRecord{0, 0, 0, 70}, &a, 1);
  grid.place(2, CellRecord{0, 0, 0, 20}, &b, 1);
  grid.place(5, CellRecord{0, 0, 0, 50}, &c, 1);
  ASSERT_EQ(grid.size(), 3u);
  EXPECT_EQ(grid.siteOf(0), 2u);
  EXPECT_EQ(grid.siteOf(1), 5u);
  EXPECT_EQ(grid.siteOf(2), 7u);
  EXPECT_EQ(grid.cells()[0].id, 20u);
  EXPECT_EQ(*grid.stateOf(grid.cells()[0]), 2.0);
  EXPECT_EQ(*grid.stateOf(grid.cells()[2]), 1.0);
  EXPECT_EQ(grid.cellAt(5), 1u);
  EXPECT_EQ(grid.cellAt(0), GridPool::kEmpty);
  EXPECT_THROW(grid.place(5, CellRecord{}, &a, 1), std::logic_error);
}

}  // namespace
}  // namespace ontogen
