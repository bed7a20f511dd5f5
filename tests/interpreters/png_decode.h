#pragma once
// Reads a PNG back through libpng, an independent decoder, for the tests.

#include <png.h>

#include <cstdint>
#include <filesystem>
#include <vector>

namespace ontogen::testing_support {

struct DecodedPng {
  bool ok = false;
  int width = 0, height = 0;
  std::vector<uint8_t> rgb;  ///< 3 bytes per pixel, rows from the top
};

inline DecodedPng decodePng(const std::filesystem::path& file) {
  DecodedPng d;
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&image, file.c_str())) return d;
  image.format = PNG_FORMAT_RGB;
  d.rgb.resize(PNG_IMAGE_SIZE(image));
  if (!png_image_finish_read(&image, nullptr, d.rgb.data(), 0, nullptr)) return d;
  d.ok = true;
  d.width = static_cast<int>(image.width);
  d.height = static_cast<int>(image.height);
  return d;
}

}  // namespace ontogen::testing_support
