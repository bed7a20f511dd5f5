#pragma once
// Draws a time-state diagram (paper 002, Fig. 5) as SVG: time across, one row per cell,
// bars coloured by label, a system's cells under its cell's row, indented and joined to
// it by a bracket line.

#include <filesystem>
#include <string>

#include "interpreters/timeline/timeline_recorder.h"

namespace ontogen {

/// Writes the diagram atomically; throws OutputError if the file cannot be written.
void writeTimelineSvg(const std::filesystem::path& path, const Timeline& timeline, const std::string& title);

/// The SVG text itself (for tests and for other outputs).
std::string timelineSvg(const Timeline& timeline, const std::string& title);

}  // namespace ontogen
