#pragma once
// A frame's mesh regrouped for writers whose vertices carry every attribute at once
// (glTF, PLY, the renderer): one batch per palette colour, each corner's (position,
// normal, texcoord) triple made into one vertex, shared by the triangles that use the
// same triple; and the segments per colour.

#include <cstddef>
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

/// A corner of a triangle as a mesh holds it: its position, normal and texcoord indices
/// (and the cell that drew it, where a writer keeps cells apart). Triangles that share a
/// key share one vertex.
struct CornerKey {
  uint32_t position = 0, normal = 0, texcoord = 0;
  uint32_t cell = 0;  ///< 0 where cells are not told apart
  bool operator==(const CornerKey&) const = default;
};

/// The hash of a corner for unordered maps.
struct CornerHash {
  std::size_t operator()(const CornerKey& k) const {
    uint64_t h = k.position * 0x9E3779B97F4A7C15ull;
    h ^= (k.normal + 0x632BE59BD9B4E019ull) * 0xC2B2AE3D27D4EB4Full;
    h ^= (k.texcoord + 0x85EBCA77C2B2AE63ull) * 0x165667B19E3779F9ull;
    h ^= (k.cell + 0x27D4EB2F165667C5ull) * 0x94D049BB133111EBull;
    return static_cast<std::size_t>(h ^ (h >> 29));
  }
};

/// The batches of geometry, by increasing palette index, only colours in use.
std::vector<MeshBatch> batchByMaterial(const Geometry& geometry);

}  // namespace ontogen
