#include "interpreters/formats/ply_writer.h"

#include <algorithm>
#include <cmath>

#include "interpreters/formats/mesh_batches.h"
#include "interpreters/palette.h"

namespace ontogen {

namespace {

int channel(double value) { return static_cast<int>(std::lround(std::clamp(value, 0.0, 1.0) * 255.0)); }

}  // namespace

void writePly(const Geometry& geometry, std::ostream& out) {
  const std::vector<MeshBatch> batches = batchByMaterial(geometry);
  std::size_t vertices = 0, faces = 0;
  for (const MeshBatch& b : batches) {
    vertices += b.positions.size();
    faces += b.indices.size() / 3;
  }
  out << "ply\nformat ascii 1.0\ncomment ontogen geometry\n"
      << "element vertex " << vertices << "\n"
      << "property float x\nproperty float y\nproperty float z\n"
      << "property float nx\nproperty float ny\nproperty float nz\n"
      << "property float s\nproperty float t\n"
      << "property uchar red\nproperty uchar green\nproperty uchar blue\n"
      << "element face " << faces << "\nproperty list uchar uint vertex_indices\nend_header\n";
  out.precision(9);
  for (const MeshBatch& b : batches) {
    Color c = paletteColor(b.material);
    const int r = channel(c.r), g = channel(c.g), bl = channel(c.b);
    for (std::size_t i = 0; i < b.positions.size(); ++i) {
      const glm::vec3& p = b.positions[i];
      const glm::vec3& n = b.normals[i];
      const glm::vec2& t = b.texcoords[i];
      out << p.x << ' ' << p.y << ' ' << p.z << ' ' << n.x << ' ' << n.y << ' ' << n.z << ' ' << t.x << ' ' << t.y
          << ' ' << r << ' ' << g << ' ' << bl << '\n';
    }
  }
  std::size_t base = 0;
  for (const MeshBatch& b : batches) {
    for (std::size_t i = 0; i < b.indices.size(); i += 3) {
      out << "3 " << base + b.indices[i] << ' ' << base + b.indices[i + 1] << ' ' << base + b.indices[i + 2] << '\n';
    }
    base += b.positions.size();
  }
}

}  // namespace ontogen
