#include "interpreters/formats/mesh_batches.h"

#include <array>
#include <unordered_map>

#include "interpreters/palette.h"

namespace ontogen {

std::vector<MeshBatch> batchByMaterial(const Geometry& geometry) {
  const Mesh& mesh = geometry.mesh();
  std::array<MeshBatch, kPaletteSize> all;
  std::array<std::unordered_map<CornerKey, uint32_t, CornerHash>, kPaletteSize> corners;
  for (const Triangle& t : mesh.triangles) {
    const uint32_t m = t.material % kPaletteSize;
    MeshBatch& batch = all[m];
    for (int k = 0; k < 3; ++k) {
      const CornerKey key{t.position[k], t.normal[k], t.texcoord[k], 0};
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
