#pragma once
// A software renderer for pictures of a frame on machines with no display and no GPU.
//
// The camera frames a box (the geometry's bounds, or RenderDef::framing, which a movie
// sets to the union of its frames so that the camera stays put) from an azimuth about
// the world's up axis (y) and an elevation above the horizontal plane: a perspective
// camera (RenderDef::fieldOfView) placed as near as lets every corner of the box fit in
// the picture with its margin, the box then centred; or orthographic. A model that is
// flat in x-y is seen from the front by default, any other from azimuth 30, elevation 20.
//
// Two passes over a 2 x 2 supersampled canvas. The first rasterises triangles and lines
// into a depth buffer of 1/distance (which is linear across the picture, so it
// interpolates exactly), keeping which triangle or line each sample sees. The second
// shades each sample once: the normal is interpolated from the mesh's per-corner normals
// (perspective-correct), so generalized cylinders and surfaces are smooth and the caps of
// cylinders and the facets of the cube stay flat, as the mesh says; the light is a key
// light from above the viewer's left shoulder whose shadow is looked up in a shadow map
// (an orthographic depth picture from the light) with percentage-closer filtering over a
// soft edge, plus a fill light at the viewer and an ambient term, in linear light
// (Look). The floor under a model (the plane through its lowest point) takes the
// shadow too: the background darkens where it falls. Lines are drawn unlit.
//
// Everything runs on one thread in a fixed order: the same geometry and RenderDef give
// the same bytes on every run.

#include <cstdint>
#include <optional>
#include <vector>

#include <glm/vec3.hpp>

#include "interpreters/formats/look.h"
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
  /// Of the perspective camera, degrees across the picture's shorter side, 0..120;
  /// 0: orthographic. 30 is a normal lens (about 80 mm on 35 mm film): depth reads and
  /// nothing is stretched.
  double fieldOfView = 30;
  Look look{};                       ///< background, lights and palette
};

/// 8-bit RGB pixels, row by row from the top.
struct Image {
  int width = 0;
  int height = 0;
  std::vector<uint8_t> rgb;  ///< 3 bytes per pixel
};

/// The background of the default look (R, G, B).
inline constexpr uint8_t kBackground[3] = {245, 245, 242};

/// Where the camera of a picture stands, in the picture's pixels.
struct CameraView {
  glm::dvec3 centre{0.0};      ///< the framed box's centre, model units
  glm::dvec3 eye{0.0};         ///< perspective: where the camera is; orthographic: unused
  glm::dvec3 right{1, 0, 0};   ///< unit, the picture's +x
  glm::dvec3 up{0, 1, 0};      ///< unit, the picture's -y (rows run down)
  glm::dvec3 towardsEye{0, 0, 1};  ///< unit, from the scene to the viewer
  glm::dvec3 keyLight{0, 1, 0};    ///< unit, from the scene to the key light
  bool perspective = true;
  double distance = 1;         ///< perspective: from the eye to the centre, model units
  double focal = 1;            ///< pixels per unit of x/z (perspective) or per model unit (orthographic)
  double cx = 0, cy = 0;       ///< where the view axis meets the picture, pixels from the top left
  bool flat = false;           ///< the box is flat in x-y (no floor is drawn)

  /// Where point lands: x and y in pixels from the picture's top left corner, and its
  /// distance from the eye along the view axis (orthographic: from the centre's plane,
  /// negative towards the viewer).
  glm::dvec3 project(const glm::dvec3& point) const;
};

/// The camera renderGeometry uses for geometry under def. Throws std::invalid_argument
/// when def is out of range.
CameraView cameraOf(const Geometry& geometry, const RenderDef& def);

/// Throws std::invalid_argument when def is out of range.
void checkRenderDef(const RenderDef& def);

/// Bytes rendering a picture of def's size takes while it is made and written: the
/// supersampled canvas (depth and what each sample sees), the shadow map, the picture
/// and its PNG.
uint64_t renderBytes(const RenderDef& def);

/// Renders geometry. Throws std::invalid_argument when def is out of range, and
/// std::length_error past 2^31 - 1 triangles or lines.
Image renderGeometry(const Geometry& geometry, const RenderDef& def = {});

}  // namespace ontogen
