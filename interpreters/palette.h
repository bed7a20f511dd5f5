#pragma once
// The colours that `color(i)` selects. Every writer (OBJ's MTL, glTF materials, PNG,
// PLY vertex colours) reads the same table, so a model looks the same in all of them.

#include <array>
#include <cstdint>
#include <string>

namespace ontogen {

/// A linear RGB colour, each channel in [0, 1].
struct Color {
  double r = 0;
  double g = 0;
  double b = 0;
};

/// Colours in the palette: 16 tell branches, petals and facets apart while staying
/// distinct from each other.
inline constexpr uint32_t kPaletteSize = 16;

/// The colour of palette index i (taken modulo kPaletteSize).
Color paletteColor(uint32_t index);

/// The material name writers give palette index i: "ontogen_<i mod 16>".
std::string materialName(uint32_t index);

}  // namespace ontogen
