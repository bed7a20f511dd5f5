#include "interpreters/image/image_set.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "interpreters/formats/movie_writer.h"
#include "interpreters/formats/picture_output.h"
#include "interpreters/formats/renderer.h"
#include "interpreters/output_file.h"
#include "model/message_number.h"

namespace ontogen {

std::array<uint8_t, 3> colourMap(double t) {
  if (std::isnan(t)) return {0, 0, 0};
  // Five stops of viridis, linearly interpolated.
  static constexpr double kStops[5][3] = {
      {68, 1, 84}, {59, 82, 139}, {33, 145, 140}, {94, 201, 98}, {253, 231, 37}};
  t = std::clamp(t, 0.0, 1.0) * 4;
  const int i = std::min(static_cast<int>(t), 3);
  const double f = t - i;
  std::array<uint8_t, 3> rgb{};
  for (int c = 0; c < 3; ++c)
    rgb[c] = static_cast<uint8_t>(std::lround(kStops[i][c] + f * (kStops[i + 1][c] - kStops[i][c])));
  return rgb;
}

ImageSet::ImageSet(const ImageSetDef& def) : def_(def) {
  if (def_.movie && !ffmpegAvailable())
    throw std::invalid_argument("the mp4 format needs ffmpeg, which is not installed (Debian: apt-get install ffmpeg)");
  if (!(def_.framesPerSecond > 0)) throw std::invalid_argument("framesPerSecond must be > 0");
}

ImageSet::~ImageSet() = default;

void ImageSet::beginFrame(const FrameTarget& target) {
  target_ = target;
  sites_.clear();
  low_ = 0;
  high_ = 1;
}

void ImageSet::execute(std::string_view command, std::span<const double> args) {
  if (command == "range" && args.size() >= 2) {
    low_ = args[0];
    high_ = args[1];
    return;
  }
  if (command != "pixel" || args.size() < 3) return;
  const double x = std::round(args[0]), y = std::round(args[1]);
  if (!(x >= 0 && y >= 0 && x < kMaxImageSide && y < kMaxImageSide))
    refuse("pixel(" + messageNumber(args[0]) + ", " + messageNumber(args[1]) +
           ") is outside the picture: a site's coordinates are whole numbers 0 to " + std::to_string(kMaxImageSide - 1));
  const double span = high_ - low_;
  const double t = span != 0 ? (args[2] - low_) / span : 0.5;
  sites_.push_back({static_cast<int>(x), static_cast<int>(y), t});
}

std::vector<std::filesystem::path> ImageSet::endFrame() {
  std::vector<std::filesystem::path> written;
  const Image image = picture();
  if (def_.pictures) written.push_back(writePicture(image, target_));
  if (def_.movie) {
    const std::filesystem::path path = target_.directory / ((target_.stem.empty() ? "image" : target_.stem) + ".mp4");
    if (!movie_) movie_ = std::make_unique<MovieWriter>(path, def_.framesPerSecond);
    movie_->addFrame(image);
    if (target_.frame + 1 >= target_.frameCount) {
      movie_->finish();
      movie_.reset();
      written.push_back(path);
    }
  }
  return written;
}

Image ImageSet::picture() const {
  int columns = 1, rows = 1;
  for (const PaintedSite& site : sites_) {
    columns = std::max(columns, site.x + 1);
    rows = std::max(rows, site.y + 1);
  }
  // By the longer side, so that a tall grid is no taller than a wide one is wide.
  const int scale = std::max(1, 512 / std::max(columns, rows));
  Image image;
  image.width = columns * scale;
  image.height = rows * scale;
  image.rgb.assign(static_cast<size_t>(image.width) * image.height * 3, 0);
  for (const PaintedSite& site : sites_) {
    const auto rgb = colourMap(site.value);
    // Row 0 at the bottom, as the grid's y axis points up.
    const int top = (rows - 1 - site.y) * scale;
    for (int dy = 0; dy < scale; ++dy)
      for (int dx = 0; dx < scale; ++dx) {
        const size_t at = (static_cast<size_t>(top + dy) * image.width + site.x * scale + dx) * 3;
        std::copy(rgb.begin(), rgb.end(), image.rgb.begin() + static_cast<std::ptrdiff_t>(at));
      }
  }
  return image;
}

}  // namespace ontogen
