#pragma once
// A frame's mesh regrouped for writers whose vertices carry every attribute at once
// (glTF, PLY, the renderer): one batch per palette colour, each corner's (position,
// normal, texcoord) triple made into one vertex, shared by the triangles that use the
// same triple; and the segments per colour.

#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "interpreters/geometry.h"

namespace ontogen {

/// The triangles and lines of one palette colour.
struct MeshBatch {
  uint32_t material = 0;             ///< palette index, < kPaletteSize
  std::vector<glm::vec3> positions;  ///< model units
  std::vector<glm::vec3> normals;    ///< unit length
  std::vector<glm::vec2> texcoords;  ///< (u, v)
  std::vector<uint32_t> indices;     ///< three per triangle, anticlockwise from outside
  std::vector<glm::vec3> lines;      ///< two per segment
};

/// The batches of geometry, by increasing palette index, only colours in use.
std::vector<MeshBatch> batchByMaterial(const Geometry& geometry);

}  // namespace ontogen
