#include "interpreters/obj_writer.h"

#include <charconv>
#include <cstddef>
#include <string>

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

}  // namespace

void writeObj(const Geometry& geometry, std::ostream& out) {
  const Mesh& mesh = geometry.mesh();
  const std::vector<Segment>& segments = geometry.segments();
  std::size_t lineVertices = 0;
  for (std::size_t i = 0; i < segments.size(); ++i) lineVertices += continues(segments, i) ? 1 : 2;

  out << "# ontogen geometry\n"
      << "# " << mesh.positions.size() + lineVertices << " vertices, " << mesh.normals.size()
      << " normals, " << mesh.triangles.size() << " triangles, " << segments.size()
      << " line segments\n";
  for (const glm::dvec3& p : mesh.positions) writeVector(out, "v", p);
  for (std::size_t i = 0; i < segments.size(); ++i) {
    if (!continues(segments, i)) writeVector(out, "v", segments[i].start);
    writeVector(out, "v", segments[i].end);
  }
  for (const glm::dvec3& n : mesh.normals) writeVector(out, "vn", n);
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
}

}  // namespace ontogen
