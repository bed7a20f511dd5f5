#include "interpreters/palette.h"

#include <algorithm>
#include <cmath>

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
    // The stress ramp, blue to red through violet (paper 004 section VIII).
    {0.15, 0.25, 0.90},  // 16
    {0.28, 0.24, 0.80},  // 17
    {0.41, 0.23, 0.70},  // 18
    {0.54, 0.22, 0.60},  // 19
    {0.66, 0.20, 0.46},  // 20
    {0.77, 0.18, 0.34},  // 21
    {0.86, 0.16, 0.22},  // 22
    {0.95, 0.12, 0.10},  // 23
}};

}  // namespace

Color paletteColor(uint32_t index) { return kPalette[index % kPaletteSize]; }

uint32_t stressMaterial(double stress) {
  const double s = std::isnan(stress) ? 0.0 : std::clamp(stress, 0.0, 1.0);
  return kUserColors + static_cast<uint32_t>(std::lround(s * (kStressColors - 1)));
}

double linearFromSrgb(double channel) {
  const double c = std::clamp(channel, 0.0, 1.0);
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

Color linearColor(const Color& color) {
  return {linearFromSrgb(color.r), linearFromSrgb(color.g), linearFromSrgb(color.b)};
}

std::string materialName(uint32_t index) {
  return "ontogen_" + std::to_string(index % kPaletteSize);
}

}  // namespace ontogen
