#include "interpreters/formats/picture_output.h"

#include <cstdio>
#include <string>

#include "interpreters/formats/png_writer.h"
#include "interpreters/output_file.h"

namespace ontogen {

std::filesystem::path writePicture(const Image& image, const FrameTarget& target) {
  std::string name = target.stem;
  if (target.frameCount > 1) {
    char number[16];
    std::snprintf(number, sizeof number, "_%04d", target.frame);
    name += number;
  }
  const std::filesystem::path path = target.directory / (name + ".png");
  writeFileAtomically(path, [&](std::ostream& out) { writePng(image, out); });
  return path;
}

}  // namespace ontogen
