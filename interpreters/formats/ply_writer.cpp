#include "interpreters/formats/ply_writer.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "interpreters/formats/mesh_batches.h"
#include "interpreters/palette.h"

namespace ontogen {

namespace {

uint8_t channel(double value) { return static_cast<uint8_t>(std::lround(std::clamp(value, 0.0, 1.0) * 255.0)); }

// Little-endian bytes whatever the machine's order.
void putUint32(std::string& bytes, uint32_t value) {
  for (int shift = 0; shift < 32; shift += 8) bytes.push_back(static_cast<char>((value >> shift) & 0xff));
}
void putFloat(std::string& bytes, float value) { putUint32(bytes, std::bit_cast<uint32_t>(value)); }

}  // namespace

void writePly(const Geometry& geometry, std::ostream& out, const PlyOptions& options) {
  const std::vector<MeshBatch> batches = batchByMaterial(geometry);
  std::size_t vertices = 0, faces = 0;
  for (const MeshBatch& b : batches) {
    vertices += b.positions.size();
    faces += b.indices.size() / 3;
  }
  // A face's indices are 32-bit (property list uchar uint).
  if (vertices > UINT32_MAX) throw std::length_error("a .ply holds at most 2^32 - 1 vertices");
  out << "ply\nformat " << (options.binary ? "binary_little_endian" : "ascii") << " 1.0\n"
      << "comment ontogen geometry, " << (options.up == UpAxis::Z ? "z" : "y") << " up\n"
      << "element vertex " << vertices << "\n"
      << "property float x\nproperty float y\nproperty float z\n"
      << "property float nx\nproperty float ny\nproperty float nz\n"
      << "property float s\nproperty float t\n"
      << "property uchar red\nproperty uchar green\nproperty uchar blue\n"
      << "element face " << faces << "\nproperty list uchar uint vertex_indices\nend_header\n";
  if (options.binary) {
    // One batch at a time: 35 bytes a vertex, 13 a face.
    std::string bytes;
    for (const MeshBatch& b : batches) {
      const Color c = paletteColor(b.material);
      const uint8_t rgb[3] = {channel(c.r), channel(c.g), channel(c.b)};
      bytes.clear();
      bytes.reserve(b.positions.size() * 35);
      for (std::size_t i = 0; i < b.positions.size(); ++i) {
        const glm::vec3 p = toUpAxis(b.positions[i], options.up);
        const glm::vec3 n = toUpAxis(b.normals[i], options.up);
        for (float v : {p.x, p.y, p.z, n.x, n.y, n.z, b.texcoords[i].x, b.texcoords[i].y}) putFloat(bytes, v);
        bytes.append(reinterpret_cast<const char*>(rgb), 3);
      }
      out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    }
    uint32_t base = 0;
    for (const MeshBatch& b : batches) {
      bytes.clear();
      bytes.reserve(b.indices.size() / 3 * 13);
      for (std::size_t i = 0; i < b.indices.size(); i += 3) {
        bytes.push_back(3);
        for (int k = 0; k < 3; ++k) putUint32(bytes, base + b.indices[i + k]);
      }
      out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
      base += static_cast<uint32_t>(b.positions.size());
    }
    return;
  }
  out.precision(9);
  for (const MeshBatch& b : batches) {
    const Color c = paletteColor(b.material);
    const int r = channel(c.r), g = channel(c.g), bl = channel(c.b);
    for (std::size_t i = 0; i < b.positions.size(); ++i) {
      const glm::vec3 p = toUpAxis(b.positions[i], options.up);
      const glm::vec3 n = toUpAxis(b.normals[i], options.up);
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
