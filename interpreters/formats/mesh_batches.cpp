#include "interpreters/formats/mesh_batches.h"

#include <array>
#include <unordered_map>

#include "interpreters/palette.h"

namespace ontogen {

namespace {

struct CornerKey {
  uint32_t position, normal, texcoord;
  bool operator==(const CornerKey&) const = default;
};

struct CornerHash {
  std::size_t operator()(const CornerKey& k) const {
    uint64_t h = k.position * 0x9E3779B97F4A7C15ull;
    h ^= (k.normal + 0x632BE59BD9B4E019ull) * 0xC2B2AE3D27D4EB4Full;
    h ^= (k.texcoord + 0x85EBCA77C2B2AE63ull) * 0x165667B19E3779F9ull;
    return static_cast<std::size_t>(h ^ (h >> 29));
  }
};

}  // namespace

std::vector<MeshBatch> batchByMaterial(const Geometry& geometry) {
  const Mesh& mesh = geometry.mesh();
  std::array<MeshBatch, kPaletteSize> all;
  std::array<std::unordered_map<CornerKey, uint32_t, CornerHash>, kPaletteSize> corners;
  for (const Triangle& t : mesh.triangles) {
    const uint32_t m = t.material % kPaletteSize;
    MeshBatch& batch = all[m];
    for (int k = 0; k < 3; ++k) {
      CornerKey key{t.position[k], t.normal[k], t.texcoord[k]};
      auto [it, inserted] = corners[m].try_emplace(key, static_cast<uint32_t>(batch.positions.size()));
      if (inserted) {
        batch.positions.emplace_back(mesh.positions[key.position]);
        batch.normals.emplace_back(mesh.normals[key.normal]);
        batch.texcoords.emplace_back(key.texcoord < mesh.texcoords.size() ? glm::vec2(mesh.texcoords[key.texcoord])
                                                                          : glm::vec2(0.0f));
      }
      batch.indices.push_back(it->second);
    }
  }
  for (const Segment& s : geometry.segments()) {
    MeshBatch& batch = all[s.material % kPaletteSize];
    batch.lines.emplace_back(s.start);
    batch.lines.emplace_back(s.end);
  }
  std::vector<MeshBatch> used;
  for (uint32_t m = 0; m < kPaletteSize; ++m) {
    if (all[m].indices.empty() && all[m].lines.empty()) continue;
    all[m].material = m;
    used.push_back(std::move(all[m]));
  }
  return used;
}

}  // namespace ontogen
