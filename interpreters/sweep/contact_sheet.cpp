#include "interpreters/sweep/contact_sheet.h"

#include <algorithm>
#include <cmath>

#include "interpreters/formats/png_reader.h"

namespace ontogen {

namespace {
// A failed variant's tile: a pale red that reads as "wrong" beside any model's colours.
constexpr uint8_t kFailed[3] = {232, 170, 160};
// The sheet around the tiles: a shade darker than a picture's background, so that
// tiles stand apart.
constexpr uint8_t kSheet[3] = {210, 210, 206};

void fill(Image& sheet, int x0, int y0, int w, int h, const uint8_t colour[3]) {
  for (int y = y0; y < y0 + h; ++y)
    for (int x = x0; x < x0 + w; ++x)
      std::copy(colour, colour + 3, sheet.rgb.begin() + (static_cast<size_t>(y) * sheet.width + x) * 3);
}
}  // namespace

Image contactSheet(const std::vector<ContactTile>& tiles, const ContactSheetDef& def) {
  const size_t count = std::max<size_t>(1, std::min(tiles.size(), kMaxContactTiles));
  const int columns =
      def.columns > 0 ? def.columns : static_cast<int>(std::ceil(std::sqrt(static_cast<double>(count))));
  const int rows = static_cast<int>((count + columns - 1) / columns);
  Image sheet;
  sheet.width = columns * (def.tileWidth + def.margin) + def.margin;
  sheet.height = rows * (def.tileHeight + def.margin) + def.margin;
  sheet.rgb.resize(static_cast<size_t>(sheet.width) * sheet.height * 3);
  fill(sheet, 0, 0, sheet.width, sheet.height, kSheet);
  for (size_t i = 0; i < std::min(tiles.size(), kMaxContactTiles); ++i) {
    const int x0 = def.margin + static_cast<int>(i % columns) * (def.tileWidth + def.margin);
    const int y0 = def.margin + static_cast<int>(i / columns) * (def.tileHeight + def.margin);
    fill(sheet, x0, y0, def.tileWidth, def.tileHeight, tiles[i].failed ? kFailed : kBackground);
    if (tiles[i].failed || tiles[i].picture.empty()) continue;
    const std::optional<Image> picture = readPng(tiles[i].picture);
    if (!picture) continue;
    // Centred: a larger picture is cropped to its middle, a smaller one framed.
    const int dx = (picture->width - def.tileWidth) / 2, dy = (picture->height - def.tileHeight) / 2;
    for (int y = 0; y < def.tileHeight; ++y) {
      const int sy = y + dy;
      if (sy < 0 || sy >= picture->height) continue;
      for (int x = 0; x < def.tileWidth; ++x) {
        const int sx = x + dx;
        if (sx < 0 || sx >= picture->width) continue;
        const uint8_t* from = picture->rgb.data() + (static_cast<size_t>(sy) * picture->width + sx) * 3;
        std::copy(from, from + 3, sheet.rgb.begin() + (static_cast<size_t>(y0 + y) * sheet.width + x0 + x) * 3);
      }
    }
  }
  return sheet;
}

}  // namespace ontogen
