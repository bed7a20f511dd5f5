#pragma once
// Short labels drawn into a picture as pixels, for a contact sheet's tiles: a 5 x 7
// bitmap font of digits, capital letters and the signs numbers and names use
// (= . - + _ , : ( ) /), each glyph in a cell of 6 x 9 pixels. Small letters are drawn as
// capitals and any other character as `?`; the text itself is kept exactly elsewhere
// (a sheet's gallery.json).

#include <cstdint>
#include <string>
#include <vector>

#include "interpreters/formats/renderer.h"

namespace ontogen {

inline constexpr int kLabelGlyphWidth = 6;   ///< pixels a character takes across, its spacing included
inline constexpr int kLabelLineHeight = 9;   ///< pixels a line takes down, its spacing included

/// The lines `text` is drawn in within `width` pixels: broken at spaces, at most
/// `maxLines` of them, a word or a last line too long cut short with "..".
std::vector<std::string> labelLines(const std::string& text, int width, int maxLines);

/// Draws `lines` from (x, y) (the first line's top left) in `colour`, clipped to the
/// image and to the box x .. x + width, y .. y + height.
void drawLabel(Image& image, int x, int y, int width, int height, const std::vector<std::string>& lines,
               const uint8_t colour[3]);

}  // namespace ontogen
