// A contact sheet's labels: broken at spaces into the lines that fit a tile, cut short
// past its lines, and drawn as the font's pixels.

#include <gtest/gtest.h>

#include "interpreters/sweep/tile_label.h"

namespace ontogen::test {
namespace {

TEST(TileLabel, LinesBreakAtSpacesToFitTheTile) {
  // 64 pixels hold 10 characters of 6.
  EXPECT_EQ(labelLines("LEN=2 SHRINK=0.7", 64, 2), (std::vector<std::string>{"LEN=2", "SHRINK=0.7"}));
  EXPECT_EQ(labelLines("LEN=2 SHRINK=0.7", 128, 2), (std::vector<std::string>{"LEN=2 SHRINK=0.7"}));
  // Past the last line the label is cut short with "..", and so is a word too long.
  EXPECT_EQ(labelLines("A=1 B=2 C=3 D=4 E=5", 48, 2), (std::vector<std::string>{"A=1 B=2", "C=3 D=.."}));
  EXPECT_EQ(labelLines("BRANCHING=0.123456", 48, 2), (std::vector<std::string>{"BRANCH.."}));
  EXPECT_TRUE(labelLines("LEN=2", 5, 2).empty()) << "no character fits";
  EXPECT_TRUE(labelLines("", 64, 2).empty());
}

// "1" is 10 pixels of the font, in its 5 x 7 cell from the label's corner; a small letter
// is drawn as its capital, and nothing is drawn past the box.
TEST(TileLabel, GlyphsAreDrawnAsTheirPixelsWithinTheBox) {
  Image image{20, 10, std::vector<uint8_t>(20 * 10 * 3, 255)};
  const uint8_t ink[3] = {0, 0, 0};
  auto inked = [&image] {
    int count = 0;
    for (size_t i = 0; i < image.rgb.size(); i += 3) count += image.rgb[i] == 0;
    return count;
  };
  drawLabel(image, 2, 1, 18, 9, {"1"}, ink);
  EXPECT_EQ(inked(), 10);
  EXPECT_EQ(image.rgb[(1 * 20 + 4) * 3], 0) << "the top of the 1, its middle column";
  EXPECT_EQ(image.rgb[(7 * 20 + 3) * 3], 0) << "its foot's left end";
  Image capital = image, small = image;
  std::fill(capital.rgb.begin(), capital.rgb.end(), 255);
  std::fill(small.rgb.begin(), small.rgb.end(), 255);
  drawLabel(capital, 0, 0, 20, 10, {"E"}, ink);
  drawLabel(small, 0, 0, 20, 10, {"e"}, ink);
  EXPECT_EQ(capital.rgb, small.rgb);
  std::fill(image.rgb.begin(), image.rgb.end(), 255);
  drawLabel(image, 0, 0, 3, 9, {"8"}, ink);  // the box cuts the glyph to its 3 left columns
  EXPECT_EQ(inked(), 2 + 1 + 1 + 2 + 1 + 1 + 2);
}

}  // namespace
}  // namespace ontogen::test
