#pragma once
// Predefined surfaces (paper 000 section 4; ABOP's predefined leaves and petals): a
// triangle mesh in its own coordinates that the turtle places at its frame, scaled. A
// surface comes from an OBJ file (obj_reader.h, the #surface directive) or from a
// bicubic Bezier patch written in the language (patch ... endpatch).
//
// Surface coordinates map to the turtle's frame as x -> H x U (the turtle's right, -L),
// y -> H, z -> U: at the turtle's initial frame a surface appears as written in its file.
// Blends interpolate surfaces of one topology vertex by vertex (the flower head of paper
// 000 section 5.2 interpolates three).

#include <array>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "interpreters/geometry.h"

namespace ontogen {

/// A surface that cannot be made (unreadable file, bad patch, blend of different shapes).
class SurfaceError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// An indexed triangle mesh in surface coordinates.
struct Surface {
  std::vector<glm::dvec3> positions;                 ///< surface units
  std::vector<glm::dvec2> texcoords;                 ///< one per position, or none
  std::vector<std::array<uint32_t, 3>> triangles;    ///< position indices, anticlockwise
};

/// The 16 control points of a bicubic Bezier patch, row by row: points[4 * j + i] is
/// control point i along u of row j along v.
using PatchControls = std::array<glm::dvec3, 16>;

/// The patch sampled on a (resolution + 1)^2 grid of (u, v), two triangles per cell,
/// with texture coordinates (u, v). Throws SurfaceError unless 1 <= resolution <= 256.
Surface bezierPatch(const PatchControls& controls, int resolution);

/// The vertex-wise blend sum(w_i p_i) / sum(w_i) of surfaces that share one topology
/// (the same position count and triangles). Throws SurfaceError, naming the
/// surfaces by their position in the list, when the topologies differ, the lists'
/// sizes differ or the weights sum to 0. Weights (1, 0, ...) give the first surface.
Surface blendSurfaces(std::span<const Surface* const> surfaces, std::span<const double> weights);

/// Where and how big a surface is placed: the turtle's position and frame.
struct SurfacePlacement {
  glm::dvec3 origin{0.0};                ///< model units
  glm::dvec3 right{1.0, 0.0, 0.0};       ///< H x U, unit: the surface's x
  glm::dvec3 heading{0.0, 1.0, 0.0};     ///< H, unit: the surface's y
  glm::dvec3 up{0.0, 0.0, 1.0};          ///< U, unit: the surface's z
  double scale = 1;                      ///< model units per surface unit, > 0
};

/// The surface placed in the model as a Mesh for Geometry::addMesh, with smooth normals
/// (area-weighted over the triangles around each position; a position on no triangle,
/// or on degenerate ones only, gets the placement's up).
Mesh placeSurface(const Surface& surface, const SurfacePlacement& placement);

}  // namespace ontogen
