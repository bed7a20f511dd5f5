// Plates and the gap filter of paper 004 section VIII: attractors open gaps in a
// triangle surface; the filter closes every one and colours facets by their stretch.
#include <algorithm>
#include <map>
#include <set>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "interpreters/geometry/gap_filter.h"
#include "interpreters/geometry/turtle.h"
#include "interpreters/palette.h"

namespace ontogen {
namespace {

void x(Turtle& turtle, Geometry& geometry, const char* command, std::vector<double> args = {}) {
  ASSERT_TRUE(turtle.execute(command, args, geometry)) << command;
}

// The parallelogram of models/triangles_attracted.cell: rows of pairs of triangles (up,
// then down), each row drawn as one chain of plates; rows start a unit apart along the
// direction 60 degrees left of H.
void drawParallelogram(Turtle& turtle, Geometry& geometry, int rows, int pairs) {
  auto up = [&] {
    x(turtle, geometry, "plate"); x(turtle, geometry, "F"); x(turtle, geometry, "+", {120});
    x(turtle, geometry, "F"); x(turtle, geometry, "endplate"); x(turtle, geometry, "-", {120});
  };
  auto down = [&] {
    x(turtle, geometry, "plate"); x(turtle, geometry, "F"); x(turtle, geometry, "-", {120});
    x(turtle, geometry, "F"); x(turtle, geometry, "endplate"); x(turtle, geometry, "+", {120});
  };
  for (int r = 0; r < rows; ++r) {
    x(turtle, geometry, "[");
    for (int p = 0; p < pairs; ++p) {
      up();
      down();
    }
    x(turtle, geometry, "]");
    x(turtle, geometry, "+", {60}); x(turtle, geometry, "f"); x(turtle, geometry, "-", {60});
  }
}

void addEnvironment(Turtle& turtle, Geometry& geometry) {
  x(turtle, geometry, "attractor", {3, 5, 3, 0.05, 3});
  x(turtle, geometry, "repeller", {7, 2, -2, 0.04, 2});
}

using Edge = std::pair<uint32_t, uint32_t>;

// Edges that only one triangle uses, undirected.
std::vector<Edge> boundaryEdges(const Mesh& mesh) {
  std::map<Edge, int> uses;
  for (const Triangle& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) {
      uint32_t a = t.position[k], b = t.position[(k + 1) % 3];
      ++uses[{std::min(a, b), std::max(a, b)}];
    }
  }
  std::vector<Edge> boundary;
  for (const auto& [edge, count] : uses)
    if (count == 1) boundary.push_back(edge);
  return boundary;
}

// Closed loops the boundary edges form (connected components of the boundary graph).
int boundaryLoops(const std::vector<Edge>& edges) {
  std::map<uint32_t, std::vector<uint32_t>> next;
  for (auto [a, b] : edges) {
    next[a].push_back(b);
    next[b].push_back(a);
  }
  std::set<uint32_t> seen;
  int loops = 0;
  for (const auto& [start, ignored] : next) {
    if (seen.contains(start)) continue;
    ++loops;
    std::vector<uint32_t> stack = {start};
    while (!stack.empty()) {
      uint32_t v = stack.back();
      stack.pop_back();
      if (!seen.insert(v).second) continue;
      for (uint32_t w : next[v]) stack.push_back(w);
    }
  }
  return loops;
}

constexpr int kRows = 6;
constexpr int kPairs = 8;
constexpr double kTolerance = 0.3;

TEST(GapFilterTest, AttractorsOpenGapsThatTheFilterClosesDownToTheOuterBoundary) {
  // Without an environment the plates meet (to rounding): joined, they are one sheet.
  Turtle flat;
  Geometry flatGeometry;
  drawParallelogram(flat, flatGeometry, kRows, kPairs);
  const JoinedPlates reference = joinPlates(flat.plates(), 1e-9);
  const std::size_t triangles = static_cast<std::size_t>(kRows * 2 * kPairs);
  ASSERT_EQ(reference.mesh.triangles.size(), triangles);
  const auto outer = boundaryEdges(reference.mesh);
  // The parallelogram's outline: kPairs edges below and above, one per row at each end.
  EXPECT_EQ(outer.size(), static_cast<std::size_t>(2 * kPairs + 2 * kRows));
  EXPECT_EQ(boundaryLoops(outer), 1);
  EXPECT_LT(reference.maxStretch, 1e-12);

  Turtle bent;
  Geometry bentGeometry;
  addEnvironment(bent, bentGeometry);
  drawParallelogram(bent, bentGeometry, kRows, kPairs);
  // The attractor and the repeller moved corners apart: joined with the flat tolerance
  // the sheet has holes and cracks.
  const JoinedPlates unfiltered = joinPlates(bent.plates(), 1e-9);
  EXPECT_GT(boundaryEdges(unfiltered.mesh).size(), outer.size());
  // The filter joins them all again: the same outline, one loop, no hole inside.
  const JoinedPlates joined = joinPlates(bent.plates(), kTolerance);
  ASSERT_EQ(joined.mesh.triangles.size(), triangles);
  EXPECT_EQ(joined.mesh.positions.size(), reference.mesh.positions.size());
  const auto closed = boundaryEdges(joined.mesh);
  EXPECT_EQ(closed.size(), outer.size());
  EXPECT_EQ(boundaryLoops(closed), 1);
  EXPECT_GT(joined.maxStretch, 0.0);
  EXPECT_LT(joined.maxStretch, 0.5);  // "slightly elongating the edge lengths"
}

TEST(GapFilterTest, FacetColoursRiseWithStretch) {
  for (int i = 0; i + 1 < 20; ++i) {
    EXPECT_LE(stressMaterial(i / 19.0), stressMaterial((i + 1) / 19.0));
    EXPECT_LE(paletteColor(stressMaterial(i / 19.0)).r, paletteColor(stressMaterial((i + 1) / 19.0)).r);
    EXPECT_GE(paletteColor(stressMaterial(i / 19.0)).b, paletteColor(stressMaterial((i + 1) / 19.0)).b);
  }
  EXPECT_EQ(stressMaterial(0), kUserColors);
  EXPECT_EQ(stressMaterial(1), kPaletteSize - 1);
  EXPECT_EQ(stressMaterial(7), kPaletteSize - 1);  // clamped

  Turtle bent;
  Geometry geometry;
  addEnvironment(bent, geometry);
  drawParallelogram(bent, geometry, kRows, kPairs);
  const JoinedPlates joined = joinPlates(bent.plates(), kTolerance);
  ASSERT_EQ(joined.stretch.size(), joined.mesh.triangles.size());
  std::vector<std::pair<double, uint32_t>> byStretch;
  for (std::size_t i = 0; i < joined.stretch.size(); ++i) {
    byStretch.emplace_back(joined.stretch[i], joined.mesh.triangles[i].material);
    EXPECT_EQ(joined.mesh.triangles[i].material, stressMaterial(joined.stretch[i] / joined.maxStretch));
  }
  std::sort(byStretch.begin(), byStretch.end());
  for (std::size_t i = 0; i + 1 < byStretch.size(); ++i) EXPECT_LE(byStretch[i].second, byStretch[i + 1].second);
  EXPECT_EQ(byStretch.front().second < byStretch.back().second, true);  // the ramp is used
  EXPECT_EQ(byStretch.back().second, kPaletteSize - 1);

  // With gapfilter on, the turtle adds the same coloured sheet at the end of the frame.
  x(bent, geometry, "gapfilter", {kTolerance});
  bent.finish(geometry);
  ASSERT_EQ(geometry.mesh().triangles.size(), joined.mesh.triangles.size());
  for (std::size_t i = 0; i < joined.mesh.triangles.size(); ++i) {
    EXPECT_EQ(geometry.mesh().triangles[i].material, joined.mesh.triangles[i].material);
  }
}

TEST(GapFilterTest, PlatesWithoutTheFilterKeepTheirOwnCornersAndColour) {
  Turtle turtle;
  Geometry geometry;
  x(turtle, geometry, "color", {4});
  x(turtle, geometry, "plate");
  x(turtle, geometry, "F");
  x(turtle, geometry, "+", {90});
  x(turtle, geometry, "F");
  x(turtle, geometry, "F");
  x(turtle, geometry, "endplate");  // a quad: 2 triangles
  x(turtle, geometry, "plate");
  x(turtle, geometry, "F");
  x(turtle, geometry, "endplate");  // 2 corners: skipped, with a warning
  turtle.finish(geometry);
  EXPECT_EQ(geometry.segmentCount(), 0u);  // F inside a plate draws no line
  ASSERT_EQ(geometry.mesh().triangles.size(), 2u);
  EXPECT_EQ(geometry.mesh().triangles[0].material, 4u);
  EXPECT_EQ(turtle.warnings().badArguments, 1);
  EXPECT_NEAR(geometry.bounds().max.y, 1, 1e-12);
  EXPECT_NEAR(geometry.bounds().min.x, -2, 1e-12);
}

}  // namespace
}  // namespace ontogen
