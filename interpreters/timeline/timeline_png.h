#pragma once
// Draws a time-state diagram (paper 002, Fig. 5) as a PNG picture: the same bars,
// colours, nesting brackets and time ticks as the SVG, without text (the SVG carries the
// labels, the legend and the numbers).

#include <filesystem>

#include "interpreters/timeline/timeline_recorder.h"
#include "interpreters/formats/renderer.h"

namespace ontogen {

/// The picture itself: 1000 pixels wide, rows of 1 to 14 pixels.
Image timelineImage(const Timeline& timeline);

/// Writes the picture atomically; throws OutputError if the file cannot be written.
void writeTimelinePng(const std::filesystem::path& path, const Timeline& timeline);

}  // namespace ontogen
