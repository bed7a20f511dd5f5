#pragma once
// The output stage of pictures made by a set (the image set's grid): writes a frame's
// picture as DIR/<stem>.png, or DIR/<stem>_0003.png when the run has several frames,
// atomically.

#include <filesystem>

#include "interpreters/formats/renderer.h"
#include "interpreters/interpretation_set.h"

namespace ontogen {

/// Writes `image` for the frame `target`; returns the path. Throws OutputError.
std::filesystem::path writePicture(const Image& image, const FrameTarget& target);

}  // namespace ontogen
