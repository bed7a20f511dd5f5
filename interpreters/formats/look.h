#pragma once
// The look of a picture: its background, its lights and how the palette is shown. A few
// named looks (`--look`, `#look`) so that a picture suits a light page, a dark page or
// print without a painter's settings; RenderDef holds one, and a test or a host may make
// its own. Intensities are in linear light: the renderer lights a colour in linear light
// (palette.h's linearFromSrgb) and encodes the sum as sRGB again.

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace ontogen {

/// How pictures are lit and coloured; all intensities in linear light, 0..1 shares.
struct Look {
  std::string_view name = "light";
  std::array<uint8_t, 3> background{245, 245, 242};  ///< sRGB, the picture's empty parts
  /// A lit surface's colour is albedo x (ambient + fill |n.v| + key max(0, n.l) shadow)
  /// + specular (n.h)^shininess shadow, n the surface's normal towards the viewer, v the
  /// direction to the viewer, l to the key light, h halfway between l and v.
  double ambient = 0.22;
  double fill = 0.28;         ///< a light at the viewer: faces seen head-on are never dark
  double key = 0.75;          ///< the key light, from above the viewer's left shoulder
  double specular = 0.08;     ///< a white highlight of the key light
  double shininess = 24;      ///< of the highlight: higher is smaller and sharper
  /// The floor under the model (the plane through its lowest point, seen from above)
  /// takes the key light's shadow: the background there is darkened by up to this share.
  double floorShadow = 0.35;
  /// Shadows' soft edge, as a share of the model's largest side (percentage-closer
  /// filtering over that width).
  double softness = 0.025;
  /// The palette as shown: saturation kept (1: as is, 0: grey), then mixed towards the
  /// background by `wash` (0: none).
  double saturation = 1;
  double wash = 0;
  double lineShade = 0.6;     ///< zero-radius lines drawn in their colour times this (unlit)
};

/// The named looks, in the order `ontogen help` and the errors list them.
std::vector<std::string_view> lookNames();

/// The look of that name, or nothing.
std::optional<Look> findLook(std::string_view name);

/// "light, dark, paper".
std::string lookList();

}  // namespace ontogen
