#pragma once
// A software renderer for pictures of a frame on machines with no display and no GPU:
// orthographic camera that frames the model's bounding box automatically (or a box it is
// given, RenderDef::framing), z-buffer,
// flat Lambert shading of each triangle by a light beside the viewer (two-sided, since
// discs have one side), segments as lines, 2 x 2 supersampling for smooth edges.
//
// The view is given as an azimuth about the world's up axis (y) and an elevation above
// the horizontal plane, in degrees; a model that is flat in x-y is seen from the front by
// default, any other from azimuth 30, elevation 20.

#include <cstdint>
#include <optional>
#include <vector>

#include "interpreters/geometry.h"

namespace ontogen {

/// How a picture is taken; validated by renderGeometry.
struct RenderDef {
  int width = 800;                   ///< pixels, 1..8192
  int height = 800;                  ///< pixels, 1..8192
  std::optional<double> azimuth;     ///< degrees about +y from +z towards +x; default: see above
  std::optional<double> elevation;   ///< degrees above the horizontal, -90..90
  double margin = 0.05;              ///< fraction of the picture left around the model
  /// The box the camera frames (and whose shape picks the default view) instead of the
  /// geometry's own bounds: a movie frames every frame on the union of all, so that the
  /// camera stays put and a model that grows is seen to grow.
  std::optional<Box> framing;
};

/// 8-bit RGB pixels, row by row from the top.
struct Image {
  int width = 0;
  int height = 0;
  std::vector<uint8_t> rgb;  ///< 3 bytes per pixel
};

/// The colour every picture starts from (R, G, B).
inline constexpr uint8_t kBackground[3] = {245, 245, 242};

/// Throws std::invalid_argument when def is out of range.
void checkRenderDef(const RenderDef& def);

/// Bytes rendering a picture of def's size takes while it is made and written: the
/// supersampled canvas (depth and colour), the picture and its PNG.
uint64_t renderBytes(const RenderDef& def);

/// Renders geometry. Throws std::invalid_argument when def is out of range.
Image renderGeometry(const Geometry& geometry, const RenderDef& def = {});

}  // namespace ontogen
