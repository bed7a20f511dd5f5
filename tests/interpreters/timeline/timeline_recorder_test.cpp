// The time-state diagram's data (paper 002, Fig. 5) and its SVG.

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <map>
#include <string>

#include "interpreters/timeline/timeline_recorder.h"
#include "interpreters/timeline/timeline_layout.h"
#include "interpreters/timeline/timeline_png.h"
#include "interpreters/timeline/timeline_svg.h"
#include "tests/core/test_support.h"

namespace ontogen {
namespace {

using testing_support::compileModel;

size_t count(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

// Anabaena lives by generations of one time unit: 1, 2, 3, 5, 8, 13 and 21 cells up to
// t = 6, each row exactly one unit long except the last generation, alive at the end.
TEST(Timeline, AnabaenaRowsAreItsGenerations) {
  auto program = compileModel("anabaena.cell");
  Timeline timeline = recordTimeline(program, WorldDef{}, 6, 0.5);
  ASSERT_EQ(timeline.rows.size(), 53u);
  std::map<double, int> bornAt;
  for (const TimelineRow& row : timeline.rows) {
    ++bornAt[row.born];
    EXPECT_DOUBLE_EQ(row.gone - row.born, row.born == 6 ? 0 : 1) << row.label << " born " << row.born;
    EXPECT_EQ(row.depth, 0);
  }
  EXPECT_EQ(bornAt, (std::map<double, int>{{0, 1}, {1, 2}, {2, 3}, {3, 5}, {4, 8}, {5, 13}, {6, 21}}));
  // Generations read downwards: the first row is the axiom.
  EXPECT_EQ(timeline.rows.front().born, 0);
  const std::string svg = timelineSvg(timeline, "anabaena");
  EXPECT_EQ(count(svg, "class=\"cell\""), 53u);
  EXPECT_EQ(count(svg, "class=\"legend\""), 4u);  // ar al br bl
}

// A system's cells hang under its row, one level deeper; turtle symbols get no row.
TEST(Timeline, NestedPoolsFollowTheirSystemCell) {
  auto program = compileModel("orchard.cell");
  Timeline timeline = recordTimeline(program, WorldDef{}, 3, 0.1);
  ASSERT_FALSE(timeline.rows.empty());
  EXPECT_EQ(timeline.rows[0].label, "tree");
  EXPECT_TRUE(timeline.rows[0].system);
  EXPECT_EQ(timeline.rows[1].label, "Trunk");
  EXPECT_EQ(timeline.rows[1].depth, 1);
  int branches = 0;
  for (size_t i = 0; i < timeline.rows.size(); ++i) {
    const TimelineRow& row = timeline.rows[i];
    EXPECT_NE(row.label, "[");
    EXPECT_NE(row.label, "+");
    if (row.label != "branch") continue;
    ++branches;
    EXPECT_EQ(row.depth, 1);
    ASSERT_LT(i + 2, timeline.rows.size());
    EXPECT_EQ(timeline.rows[i + 1].label, "Shoot");
    EXPECT_EQ(timeline.rows[i + 1].depth, 2);
    EXPECT_EQ(timeline.rows[i + 2].label, "Leaf");
  }
  EXPECT_EQ(branches, 6);  // a pair per tree by t = 3
}

// The PNG has the SVG's layout: each bar's middle pixel has its label's colour, and the
// plot is white where no cell lived.
TEST(Timeline, PictureBarsHaveTheirLabelsColours) {
  auto program = compileModel("anabaena.cell");
  Timeline timeline = recordTimeline(program, WorldDef{}, 6, 1);
  const TimelineLayout layout(timeline);
  const Image image = timelineImage(timeline);
  EXPECT_EQ(image.width, static_cast<int>(std::ceil(layout.width)));
  EXPECT_EQ(image.height, static_cast<int>(std::ceil(layout.height)));
  auto pixel = [&](double x, double y) {
    const size_t at = (static_cast<size_t>(y) * image.width + static_cast<size_t>(x)) * 3;
    return std::array<uint8_t, 3>{image.rgb[at], image.rgb[at + 1], image.rgb[at + 2]};
  };
  for (size_t i = 0; i < timeline.rows.size(); ++i) {
    const TimelineRow& row = timeline.rows[i];
    if (row.gone - row.born < 0.5) continue;
    const double y = layout.rowY(i) + layout.rowHeight / 2;
    EXPECT_EQ(pixel(layout.x((row.born + row.gone) / 2), y), TimelineLayout::colours()[layout.colourIndex.at(row.label)])
        << i;
    if (row.born >= 1) {
      EXPECT_EQ(pixel(layout.x(row.born - 0.5), y), (std::array<uint8_t, 3>{255, 255, 255})) << i;
    }
  }
}

TEST(Timeline, RowsPastTheLimitAreCounted) {
  auto program = compileModel("anabaena.cell");
  Timeline timeline = recordTimeline(program, WorldDef{}, 6, 1, 10);
  EXPECT_EQ(timeline.rows.size(), 10u);
  EXPECT_EQ(timeline.omitted, 43u);
  EXPECT_NE(timelineSvg(timeline, "a").find("43 more not drawn"), std::string::npos);
}

}  // namespace
}  // namespace ontogen
