#include "interpreters/formats/png_writer.h"

#include <csetjmp>

#include <png.h>

#include "interpreters/interpretation_set.h"

namespace ontogen {

namespace {

void writeToStream(png_structp png, png_bytep data, png_size_t length) {
  auto* out = static_cast<std::ostream*>(png_get_io_ptr(png));
  out->write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(length));
}

void flushStream(png_structp png) { static_cast<std::ostream*>(png_get_io_ptr(png))->flush(); }

void ignoreWarning(png_structp, png_const_charp) {}

/// libpng reports errors by longjmp, so this holds only plain data; true on success.
bool encode(const Image& image, std::ostream& out) {
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, ignoreWarning);
  if (png == nullptr) return false;
  png_infop info = png_create_info_struct(png);
  if (info == nullptr || setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    return false;
  }
  png_set_write_fn(png, &out, writeToStream, flushStream);
  png_set_IHDR(png, info, static_cast<png_uint_32>(image.width), static_cast<png_uint_32>(image.height), 8,
               PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  for (int y = 0; y < image.height; ++y) {
    png_write_row(png, const_cast<png_bytep>(image.rgb.data() + static_cast<std::size_t>(y) * image.width * 3));
  }
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return true;
}

}  // namespace

void writePng(const Image& image, std::ostream& out) {
  if (image.width < 1 || image.height < 1 ||
      image.rgb.size() != static_cast<std::size_t>(image.width) * image.height * 3) {
    throw OutputError("PNG: the picture's size does not match its pixels");
  }
  if (!encode(image, out)) throw OutputError("PNG: libpng could not encode the picture");
}

}  // namespace ontogen
