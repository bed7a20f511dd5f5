#pragma once
// The "image" interpretation set: a picture of a grid (or any pool whose cells know
// where they are), one pixel block per site, coloured through a colour map. A cell
// paints its site with `pixel(x, y, value)`; `range(lo, hi)` sets the values that map to
// the ends of the colour map (default 0 and 1; outside, the end colours). Sites no cell
// paints stay black. The frame is written as DIR/<stem>[_NNNN].png, each site scaled up
// to a square of whole pixels so that the picture is at least 512 pixels wide; with
// `--format mp4`, every frame also goes into the movie DIR/<stem>.mp4 (and with mp4
// alone, only there). The image set has no 3-D formats: glb, obj, ply and svg ask it
// for nothing, and it writes its pictures as before.

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "interpreters/formats/renderer.h"
#include "interpreters/interpretation_set.h"

namespace ontogen {

struct PaintedSite {
  int x = 0;
  int y = 0;
  double value = 0;
};

/// The colour map (after matplotlib's viridis: dark blue, teal, green, yellow) at
/// t in [0, 1]; t outside is clamped, NaN is black.
std::array<uint8_t, 3> colourMap(double t);

struct ImageSetDef {
  bool pictures = true;        ///< a PNG a frame
  bool movie = false;          ///< every frame into DIR/<stem>.mp4 (needs ffmpeg)
  double framesPerSecond = 25; ///< of the movie
};

class MovieWriter;

class ImageSet final : public InterpretationSet {
 public:
  /// Throws std::invalid_argument when def asks for a movie and ffmpeg is missing.
  explicit ImageSet(const ImageSetDef& def = {});
  ~ImageSet() override;
  std::string_view name() const override { return "image"; }
  bool knows(std::string_view command) const override { return command == "pixel" || command == "range"; }
  void beginFrame(const FrameTarget& target) override;
  void execute(std::string_view command, std::span<const double> args) override;
  /// Writes the frame's picture through the output stage (formats/picture_output.h).
  std::vector<std::filesystem::path> endFrame() override;
  /// The picture of the sites painted so far: the frame this set produces.
  Image picture() const;

  /// The sites painted in the current frame (for tests).
  const std::vector<PaintedSite>& sites() const { return sites_; }

 private:
  ImageSetDef def_;
  std::unique_ptr<MovieWriter> movie_;
  FrameTarget target_;
  std::vector<PaintedSite> sites_;
  double low_ = 0, high_ = 1;
};

/// Most sites along a side: a picture of a larger grid is an error, not a huge file.
inline constexpr int kMaxImageSide = 8192;

}  // namespace ontogen
