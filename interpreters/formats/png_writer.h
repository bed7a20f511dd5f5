#pragma once
// PNG output of a rendered picture through libpng (8-bit RGB, no interlacing).

#include <ostream>

#include "interpreters/formats/renderer.h"

namespace ontogen {

/// Writes image to out as a PNG. Throws OutputError when libpng fails.
void writePng(const Image& image, std::ostream& out);

}  // namespace ontogen
