#include "interpreters/formats/obj_writer.h"

#include <charconv>
#include <cstddef>
#include <set>
#include <string>

#include "interpreters/palette.h"

namespace ontogen {

namespace {

// Significant digits of every coordinate: a double's 17 would only add noise digits,
// 10 keeps a 1 km model exact to the micrometre.
constexpr int kDigits = 10;

void writeNumber(std::ostream& out, double value) {
  char buffer[32];
  auto end = std::to_chars(buffer, buffer + sizeof buffer, value, std::chars_format::general,
                           kDigits).ptr;
  std::string_view text(buffer, end - buffer);
  out << (text == "-0" ? std::string_view("0") : text);
}

void writeVector(std::ostream& out, const char* tag, const glm::dvec3& v) {
  out << tag;
  for (int i = 0; i < 3; ++i) {
    out << ' ';
    writeNumber(out, v[i]);
  }
  out << '\n';
}

/// True when segment i starts where segment i - 1 ended, so it reuses that vertex.
bool continues(const std::vector<Segment>& segments, std::size_t i) {
  return i > 0 && segments[i].start == segments[i - 1].end;
}

void writeObjWith(const Geometry& geometry, std::ostream& out, std::string_view mtlName, UpAxis up);

std::set<uint32_t> usedMaterials(const Geometry& geometry) {
  std::set<uint32_t> used;
  for (const Triangle& t : geometry.mesh().triangles) used.insert(t.material % kPaletteSize);
  for (const Segment& s : geometry.segments()) used.insert(s.material % kPaletteSize);
  return used;
}

}  // namespace

void writeObj(const Geometry& geometry, std::ostream& out, UpAxis up) { writeObjWith(geometry, out, {}, up); }

void writeObj(const Geometry& geometry, std::ostream& out, std::string_view mtlName, UpAxis up) {
  writeObjWith(geometry, out, mtlName.empty() ? std::string_view("ontogen.mtl") : mtlName, up);
}

void writeMtl(const Geometry& geometry, std::ostream& out) {
  out << "# ontogen materials: the palette colours the model uses\n";
  for (uint32_t material : usedMaterials(geometry)) {
    Color c = paletteColor(material);
    out << "newmtl " << materialName(material) << "\nKd ";
    writeNumber(out, c.r);
    out << ' ';
    writeNumber(out, c.g);
    out << ' ';
    writeNumber(out, c.b);
    out << "\nKa 0 0 0\nKs 0 0 0\nd 1\nillum 1\n";
  }
}

namespace {

void writeObjWith(const Geometry& geometry, std::ostream& out, std::string_view mtlName, UpAxis up) {
  const bool materials = !mtlName.empty();
  const Mesh& mesh = geometry.mesh();
  const std::vector<Segment>& segments = geometry.segments();
  std::size_t lineVertices = 0;
  for (std::size_t i = 0; i < segments.size(); ++i) lineVertices += continues(segments, i) ? 1 : 2;

  out << "# ontogen geometry" << (up == UpAxis::Z ? ", z up" : "") << "\n"
      << "# " << mesh.positions.size() + lineVertices << " vertices, " << mesh.normals.size()
      << " normals, " << mesh.triangles.size() << " triangles, " << segments.size()
      << " line segments\n";
  if (materials) out << "mtllib " << mtlName << '\n';
  if (geometry.empty()) {
    // Readers (assimp) refuse a file without a mesh: a frame with nothing to draw holds
    // one point at the origin.
    out << "# nothing to draw in this frame: one point at the origin\nv 0 0 0\np 1\n";
    return;
  }
  for (const glm::dvec3& p : mesh.positions) writeVector(out, "v", toUpAxis(p, up));
  for (std::size_t i = 0; i < segments.size(); ++i) {
    if (!continues(segments, i)) writeVector(out, "v", toUpAxis(segments[i].start, up));
    writeVector(out, "v", toUpAxis(segments[i].end, up));
  }
  for (const glm::dvec3& n : mesh.normals) writeVector(out, "vn", toUpAxis(n, up));
  if (!materials) {
    for (const Triangle& t : mesh.triangles) {
      out << 'f';
      for (int k = 0; k < 3; ++k) out << ' ' << t.position[k] + 1 << "//" << t.normal[k] + 1;
      out << '\n';
    }
    // 1-based index of the last vertex written for the segments so far.
    std::size_t last = mesh.positions.size();
    for (std::size_t i = 0; i < segments.size(); ++i) {
      std::size_t start = continues(segments, i) ? last : ++last;
      out << "l " << start << ' ' << ++last << '\n';
    }
    return;
  }
  for (const glm::dvec2& t : mesh.texcoords) {
    out << "vt ";
    writeNumber(out, t.x);
    out << ' ';
    writeNumber(out, t.y);
    out << '\n';
  }
  // 1-based index of each segment's first vertex, in the order written above.
  std::vector<std::size_t> segmentStart(segments.size());
  std::size_t last = mesh.positions.size();
  for (std::size_t i = 0; i < segments.size(); ++i) {
    segmentStart[i] = continues(segments, i) ? last : ++last;
    ++last;
  }
  for (uint32_t material : usedMaterials(geometry)) {
    out << "usemtl " << materialName(material) << '\n';
    for (const Triangle& t : mesh.triangles) {
      if (t.material % kPaletteSize != material) continue;
      out << 'f';
      for (int k = 0; k < 3; ++k) {
        out << ' ' << t.position[k] + 1 << '/' << t.texcoord[k] + 1 << '/' << t.normal[k] + 1;
      }
      out << '\n';
    }
    for (std::size_t i = 0; i < segments.size(); ++i) {
      if (segments[i].material % kPaletteSize != material) continue;
      out << "l " << segmentStart[i] << ' ' << segmentStart[i] + 1 << '\n';
    }
  }
}

}  // namespace

}  // namespace ontogen
