#pragma once
// A contact sheet: thumbnails side by side in a grid, in order, left to right and top to
// bottom, each in a tile of the same size with a margin; a variant that failed is a
// tile of a warning colour, one with no picture a tile of the background.

#include <cstddef>
#include <filesystem>
#include <vector>

#include "interpreters/formats/renderer.h"

namespace ontogen {

struct ContactSheetDef {
  int tileWidth = 128;   ///< pixels; a thumbnail of another size is centred and cropped
  int tileHeight = 128;  ///< pixels
  int margin = 4;        ///< pixels between tiles and around them
  int columns = 0;       ///< 0: the smallest number of columns that makes the sheet square or wider
};

/// One tile: the thumbnail's file (empty: none) and whether its variant failed.
struct ContactTile {
  std::filesystem::path picture;
  bool failed = false;
};

/// A sheet holds at most this many tiles (the first ones): 1024 tiles of 128 x 128 are a
/// 4 x 4 K picture of 50 MB in memory, about what a picture of a sweep should cost.
inline constexpr size_t kMaxContactTiles = 1024;

/// The sheet of `tiles`; a thumbnail that is missing or unreadable is a background tile.
Image contactSheet(const std::vector<ContactTile>& tiles, const ContactSheetDef& def = {});

}  // namespace ontogen
