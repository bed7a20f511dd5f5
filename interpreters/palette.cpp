#include "interpreters/palette.h"

namespace ontogen {

namespace {

// 0 is the bark/stem grey-brown that undecorated models draw with; the rest follow
// plant and signal colours so that colour indices in models read naturally.
constexpr std::array<Color, kPaletteSize> kPalette = {{
    {0.62, 0.55, 0.45},  // 0 stem
    {0.20, 0.60, 0.20},  // 1 leaf green
    {0.85, 0.20, 0.20},  // 2 red
    {0.95, 0.80, 0.20},  // 3 yellow
    {0.25, 0.40, 0.85},  // 4 blue
    {0.90, 0.50, 0.75},  // 5 pink
    {0.95, 0.55, 0.15},  // 6 orange
    {0.55, 0.30, 0.75},  // 7 violet
    {0.90, 0.90, 0.90},  // 8 white
    {0.35, 0.35, 0.35},  // 9 dark grey
    {0.45, 0.30, 0.15},  // 10 brown
    {0.55, 0.85, 0.35},  // 11 light green
    {0.20, 0.75, 0.80},  // 12 cyan
    {0.70, 0.70, 0.30},  // 13 olive
    {0.80, 0.35, 0.35},  // 14 rose
    {0.15, 0.20, 0.35},  // 15 navy
}};

}  // namespace

Color paletteColor(uint32_t index) { return kPalette[index % kPaletteSize]; }

std::string materialName(uint32_t index) {
  return "ontogen_" + std::to_string(index % kPaletteSize);
}

}  // namespace ontogen
