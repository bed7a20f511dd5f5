#include "interpreters/sweep/contact_sheet.h"

#include <algorithm>
#include <cmath>
#include <fstream>

#include <nlohmann/json.hpp>

#include "interpreters/formats/png_reader.h"
#include "interpreters/output_file.h"
#include "interpreters/sweep/tile_label.h"

namespace ontogen {

namespace {
// A failed variant's tile: a pale red that reads as "wrong" beside any model's colours.
constexpr uint8_t kFailed[3] = {232, 170, 160};
// The sheet around the tiles: a shade darker than a picture's background, so that
// tiles stand apart.
constexpr uint8_t kSheet[3] = {210, 210, 206};
// Label text: dark grey, readable on the sheet.
constexpr uint8_t kLabelText[3] = {40, 40, 40};

void fill(Image& sheet, int x0, int y0, int w, int h, const uint8_t colour[3]) {
  for (int y = y0; y < y0 + h; ++y)
    for (int x = x0; x < x0 + w; ++x)
      std::copy(colour, colour + 3, sheet.rgb.begin() + (static_cast<size_t>(y) * sheet.width + x) * 3);
}

// The picture drawn into the tile at (x0, y0), shrunk by `scale` about its centre: each
// tile pixel is the mean of the picture pixels it covers; outside the picture, the
// picture's corner colour (its background).
void drawShrunk(Image& sheet, int x0, int y0, int tileWidth, int tileHeight, const Image& picture, double scale) {
  const uint8_t* corner = picture.rgb.data();
  auto source = [&](int tile, int size, int at) {
    return static_cast<int>(std::floor(size * 0.5 + (at - tile * 0.5) / scale));
  };
  for (int y = 0; y < tileHeight; ++y) {
    const int sy0 = source(tileHeight, picture.height, y);
    const int sy1 = std::max(sy0 + 1, source(tileHeight, picture.height, y + 1));
    for (int x = 0; x < tileWidth; ++x) {
      const int sx0 = source(tileWidth, picture.width, x);
      const int sx1 = std::max(sx0 + 1, source(tileWidth, picture.width, x + 1));
      double sum[3] = {0, 0, 0};
      for (int sy = sy0; sy < sy1; ++sy)
        for (int sx = sx0; sx < sx1; ++sx) {
          const bool inside = sx >= 0 && sy >= 0 && sx < picture.width && sy < picture.height;
          const uint8_t* from =
              inside ? picture.rgb.data() + (static_cast<size_t>(sy) * picture.width + sx) * 3 : corner;
          for (int c = 0; c < 3; ++c) sum[c] += from[c];
        }
      const double n = static_cast<double>(sy1 - sy0) * (sx1 - sx0);
      uint8_t* to = sheet.rgb.data() + (static_cast<size_t>(y0 + y) * sheet.width + x0 + x) * 3;
      for (int c = 0; c < 3; ++c) to[c] = static_cast<uint8_t>(std::lround(sum[c] / n));
    }
  }
}
}  // namespace

ContactSheetLayout contactSheetLayout(const std::vector<ContactTile>& tiles, const ContactSheetDef& def) {
  ContactSheetLayout layout;
  const size_t shown = std::min(tiles.size(), kMaxContactTiles);
  const size_t count = std::max<size_t>(1, shown);
  const int columns =
      def.columns > 0 ? def.columns : static_cast<int>(std::ceil(std::sqrt(static_cast<double>(count))));
  const int rows = static_cast<int>((count + columns - 1) / columns);
  bool labelled = false;
  for (size_t i = 0; i < shown; ++i) {
    labelled = labelled || !tiles[i].label.empty();
    const double scale = tiles[i].pixelsPerUnit;
    if (!tiles[i].failed && std::isfinite(scale) && scale > 0)
      layout.pixelsPerUnit = layout.pixelsPerUnit > 0 ? std::min(layout.pixelsPerUnit, scale) : scale;
  }
  layout.labelHeight = labelled ? std::max(0, def.labelLines) * kLabelLineHeight + 2 : 0;
  const int cellHeight = def.tileHeight + layout.labelHeight;
  layout.width = columns * (def.tileWidth + def.margin) + def.margin;
  layout.height = rows * (cellHeight + def.margin) + def.margin;
  for (size_t i = 0; i < shown; ++i) {
    ContactTilePlace place;
    place.x = def.margin + static_cast<int>(i % columns) * (def.tileWidth + def.margin);
    place.y = def.margin + static_cast<int>(i / columns) * (cellHeight + def.margin);
    place.labelY = place.y + def.tileHeight + 2;
    const double scale = tiles[i].pixelsPerUnit;
    if (layout.pixelsPerUnit > 0 && std::isfinite(scale) && scale > 0) place.scale = layout.pixelsPerUnit / scale;
    if (labelled) place.lines = labelLines(tiles[i].label, def.tileWidth, def.labelLines);
    layout.tiles.push_back(std::move(place));
  }
  return layout;
}

Image contactSheet(const std::vector<ContactTile>& tiles, const ContactSheetDef& def) {
  const ContactSheetLayout layout = contactSheetLayout(tiles, def);
  Image sheet;
  sheet.width = layout.width;
  sheet.height = layout.height;
  sheet.rgb.resize(static_cast<size_t>(sheet.width) * sheet.height * 3);
  fill(sheet, 0, 0, sheet.width, sheet.height, kSheet);
  for (size_t i = 0; i < layout.tiles.size(); ++i) {
    const ContactTilePlace& place = layout.tiles[i];
    fill(sheet, place.x, place.y, def.tileWidth, def.tileHeight, tiles[i].failed ? kFailed : kBackground);
    drawLabel(sheet, place.x, place.labelY, def.tileWidth, layout.labelHeight - 2, place.lines, kLabelText);
    if (tiles[i].failed || tiles[i].picture.empty()) continue;
    const std::optional<Image> picture = readPng(tiles[i].picture);
    if (!picture || picture->width <= 0 || picture->height <= 0) continue;
    drawShrunk(sheet, place.x, place.y, def.tileWidth, def.tileHeight, *picture, place.scale);
  }
  return sheet;
}

void writeContactSheetJson(const std::vector<ContactTile>& tiles, const ContactSheetDef& def, std::ostream& out) {
  const ContactSheetLayout layout = contactSheetLayout(tiles, def);
  nlohmann::json json;
  json["width"] = layout.width;
  json["height"] = layout.height;
  json["pixels_per_unit"] = layout.pixelsPerUnit;
  nlohmann::json list = nlohmann::json::array();
  for (size_t i = 0; i < layout.tiles.size(); ++i) {
    const ContactTilePlace& place = layout.tiles[i];
    list.push_back({{"picture", tiles[i].picture.filename().string()},
                    {"label", tiles[i].label},
                    {"failed", tiles[i].failed},
                    {"box", {place.x, place.y, def.tileWidth, def.tileHeight}},
                    {"label_box", {place.x, place.labelY, def.tileWidth, std::max(0, layout.labelHeight - 2)}},
                    {"scale", place.scale}});
  }
  json["tiles"] = list;
  out << json.dump() << '\n';
}

std::filesystem::path thumbnailScalePath(const std::filesystem::path& picture) {
  std::filesystem::path path = picture;
  return path.replace_extension(".json");
}

void writeThumbnailScale(const std::filesystem::path& picture, double pixelsPerUnit) {
  writeFileAtomically(thumbnailScalePath(picture),
                      [&](std::ostream& out) { out << nlohmann::json{{"pixels_per_unit", pixelsPerUnit}}.dump() << '\n'; });
}

double readThumbnailScale(const std::filesystem::path& picture) {
  std::ifstream in(thumbnailScalePath(picture), std::ios::binary);
  if (!in) return 0;
  const nlohmann::json json = nlohmann::json::parse(in, nullptr, false);
  if (!json.is_object() || !json.contains("pixels_per_unit") || !json["pixels_per_unit"].is_number()) return 0;
  const double scale = json["pixels_per_unit"].get<double>();
  return std::isfinite(scale) && scale > 0 ? scale : 0;
}

}  // namespace ontogen
