#pragma once
// The colours that `color(i)` selects. Every writer (OBJ's MTL, glTF materials, PNG,
// PLY vertex colours) reads the same table, so a model looks the same in all of them.

#include <array>
#include <cstdint>
#include <string>

namespace ontogen {

/// An RGB colour as displayed (sRGB-encoded, as a PNG or a colour picker holds it), each
/// channel in [0, 1]. Formats whose colours are linear light (glTF's baseColorFactor)
/// convert it with linearFromSrgb.
struct Color {
  double r = 0;
  double g = 0;
  double b = 0;
};

/// Colours that `color(i)` chooses from: 16 tell branches, petals and facets apart while
/// staying distinct from each other.
inline constexpr uint32_t kUserColors = 16;

/// Colours of the stress ramp of the gap filter (gap_filter.h), after the user colours:
/// 8 steps from blue to red read as a ramp without banding into noise.
inline constexpr uint32_t kStressColors = 8;

/// Every colour writers know: the user colours, then the stress ramp.
inline constexpr uint32_t kPaletteSize = kUserColors + kStressColors;

/// The colour of palette index i (taken modulo kPaletteSize).
Color paletteColor(uint32_t index);

/// The palette index of stress s in [0, 1] (clamped): kUserColors (blue, unperturbed)
/// to kPaletteSize - 1 (red, most stretched), rising with s.
uint32_t stressMaterial(double stress);

/// The linear-light value of an sRGB-encoded channel value in [0, 1] (IEC 61966-2-1).
double linearFromSrgb(double channel);
/// The colour with each channel in linear light.
Color linearColor(const Color& color);

/// The material name writers give palette index i: "ontogen_<i mod kPaletteSize>".
std::string materialName(uint32_t index);

}  // namespace ontogen
