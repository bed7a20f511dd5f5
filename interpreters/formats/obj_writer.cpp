#include "interpreters/formats/obj_writer.h"

#include <charconv>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <memory>
#include <set>
#include <string>

#include "interpreters/palette.h"

namespace ontogen {

namespace {

// Significant digits of every coordinate: a double's 17 would only add noise digits,
// 10 keeps a 1 km model exact to the micrometre.
constexpr int kDigits = 10;

// The file's text, formatted into a buffer and handed to the stream in large writes:
// through the stream's operator<<, every number and space of a large OBJ cost a sentry
// and a virtual call, more time than the turtle that drew it.
class ObjText {
 public:
  explicit ObjText(std::ostream& out) : out_(out) {}
  ObjText(const ObjText&) = delete;
  ObjText& operator=(const ObjText&) = delete;
  ~ObjText() { flush(); }

  ObjText& operator<<(char c) {
    room(1);
    buffer_[used_++] = c;
    return *this;
  }
  ObjText& operator<<(std::string_view text) {
    if (text.size() > kSize) {
      flush();
      out_.write(text.data(), static_cast<std::streamsize>(text.size()));
      return *this;
    }
    room(text.size());
    std::memcpy(buffer_ + used_, text.data(), text.size());
    used_ += text.size();
    return *this;
  }
  ObjText& operator<<(const char* text) { return *this << std::string_view(text); }
  ObjText& operator<<(std::size_t value) {
    room(kNumber);
    used_ = static_cast<std::size_t>(std::to_chars(buffer_ + used_, buffer_ + kSize, value).ptr - buffer_);
    return *this;
  }
  ObjText& operator<<(uint32_t value) { return *this << static_cast<std::size_t>(value); }
  /// kDigits significant digits, shortest form; -0 as 0.
  void number(double value) {
    room(kNumber);
    char* at = buffer_ + used_;
    char* end = std::to_chars(at, buffer_ + kSize, value, std::chars_format::general, kDigits).ptr;
    if (end - at == 2 && at[0] == '-' && at[1] == '0') {
      at[0] = '0';
      end = at + 1;
    }
    used_ = static_cast<std::size_t>(end - buffer_);
  }
  void flush() {
    if (used_ > 0) out_.write(buffer_, static_cast<std::streamsize>(used_));
    used_ = 0;
  }

 private:
  static constexpr std::size_t kSize = 1 << 16;
  static constexpr std::size_t kNumber = 32;  // the longest number written, and more
  void room(std::size_t bytes) {
    if (used_ + bytes > kSize) flush();
  }
  std::ostream& out_;
  char buffer_[kSize];
  std::size_t used_ = 0;
};

void writeVector(ObjText& out, const char* tag, const glm::dvec3& v) {
  out << tag;
  for (int i = 0; i < 3; ++i) {
    out << ' ';
    out.number(v[i]);
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

void writeMtl(const Geometry& geometry, std::ostream& stream) {
  const auto text = std::make_unique<ObjText>(stream);
  ObjText& out = *text;
  out << "# ontogen materials: the palette colours the model uses\n";
  for (uint32_t material : usedMaterials(geometry)) {
    Color c = paletteColor(material);
    out << "newmtl " << std::string_view(materialName(material)) << "\nKd ";
    out.number(c.r);
    out << ' ';
    out.number(c.g);
    out << ' ';
    out.number(c.b);
    out << "\nKa 0 0 0\nKs 0 0 0\nd 1\nillum 1\n";
  }
}

namespace {

void writeObjWith(const Geometry& geometry, std::ostream& stream, std::string_view mtlName, UpAxis up) {
  const auto text = std::make_unique<ObjText>(stream);  // 64 KiB: not on the stack
  ObjText& out = *text;
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
    out.number(t.x);
    out << ' ';
    out.number(t.y);
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
    out << "usemtl " << std::string_view(materialName(material)) << '\n';
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
