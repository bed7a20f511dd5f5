#pragma once
// A contact sheet: thumbnails side by side in a grid, in order, left to right and top to
// bottom, each in a tile of the same size with a margin; a variant that failed is a
// tile of a warning colour, one with no picture a tile of the background.
//
// All thumbnails are drawn at one scale, so that sizes compare: a thumbnail is rendered
// framed on its own model, and its scale (pixels per model unit at the model's centre)
// is written beside it (writeThumbnailScale); the sheet shrinks each about its centre to
// the smallest scale of them all, so the largest model fills its tile and a model half
// as large is drawn half as large. A thumbnail of unknown scale is drawn as it is.
// Under each tile its label (its variant's values, `LEN=2 SHRINK=0.7`) is drawn in a
// band of text; gallery.json beside the sheet says the same in full
// (writeContactSheetJson).

#include <cstddef>
#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

#include "interpreters/formats/renderer.h"

namespace ontogen {

struct ContactSheetDef {
  int tileWidth = 128;   ///< pixels; a thumbnail of another size is centred and cropped
  int tileHeight = 128;  ///< pixels
  int margin = 4;        ///< pixels between tiles and around them
  int columns = 0;       ///< 0: the smallest number of columns that makes the sheet square or wider
  int labelLines = 2;    ///< lines of label text under each tile, when any tile has a label
};

/// One tile: the thumbnail's file (empty: none) and whether its variant failed.
struct ContactTile {
  std::filesystem::path picture;
  bool failed = false;
  std::string label;          ///< drawn under the tile; empty: none
  double pixelsPerUnit = 0;   ///< the thumbnail's scale; 0: unknown (drawn as it is)
};

/// A sheet holds at most this many tiles (the first ones): 1024 tiles of 128 x 128 are a
/// 4 x 4 K picture of 50 MB in memory, about what a picture of a sweep should cost.
inline constexpr size_t kMaxContactTiles = 1024;

/// Where a tile is on the sheet and how it is drawn.
struct ContactTilePlace {
  int x = 0, y = 0;                 ///< the thumbnail's box (def's tile size), pixels from the top left
  int labelY = 0;                   ///< the top of its label band (as high as ContactSheetLayout::labelHeight)
  double scale = 1;                 ///< the thumbnail is drawn shrunk by this (1: as rendered)
  std::vector<std::string> lines;   ///< the label as drawn
};

struct ContactSheetLayout {
  int width = 0, height = 0;        ///< of the sheet, pixels
  int labelHeight = 0;              ///< of each tile's label band; 0: no labels
  double pixelsPerUnit = 0;         ///< the shared scale; 0: no thumbnail's scale is known
  std::vector<ContactTilePlace> tiles;  ///< the first kMaxContactTiles tiles
};

/// Where `tiles` go on the sheet.
ContactSheetLayout contactSheetLayout(const std::vector<ContactTile>& tiles, const ContactSheetDef& def = {});

/// The sheet of `tiles`; a thumbnail that is missing or unreadable is a background tile.
Image contactSheet(const std::vector<ContactTile>& tiles, const ContactSheetDef& def = {});

/// gallery.json: the shared scale and, per tile in order, its picture's file name, label,
/// whether it failed, its box on the sheet, its label band and the scale it is drawn at.
void writeContactSheetJson(const std::vector<ContactTile>& tiles, const ContactSheetDef& def, std::ostream& out);

/// The file beside a thumbnail that holds its scale: `<thumbnail stem>.json`.
std::filesystem::path thumbnailScalePath(const std::filesystem::path& picture);
/// Writes the scale of `picture` (pixels per model unit at the model's centre) beside it.
/// Throws OutputError as writeFileAtomically does.
void writeThumbnailScale(const std::filesystem::path& picture, double pixelsPerUnit);
/// The scale written beside `picture`; 0 when there is none or it is unreadable.
double readThumbnailScale(const std::filesystem::path& picture);

}  // namespace ontogen
