#include "interpreters/geometry/obj_reader.h"

#include <charconv>
#include <fstream>
#include <optional>
#include <string_view>
#include <vector>

namespace ontogen {

namespace {

// An OBJ file of a predefined surface is hand-sized; 16 M positions keeps indices far
// from overflow while no petal or leaf comes near.
constexpr std::size_t kMaxPositions = std::size_t{1} << 24;

std::string_view nextWord(std::string_view& rest) {
  std::size_t start = rest.find_first_not_of(" \t\r");
  if (start == std::string_view::npos) {
    rest = {};
    return {};
  }
  rest.remove_prefix(start);
  std::size_t end = rest.find_first_of(" \t\r");
  std::string_view word = rest.substr(0, end);
  rest.remove_prefix(end == std::string_view::npos ? rest.size() : end);
  return word;
}

class ObjParser {
 public:
  explicit ObjParser(std::string name) : name_(std::move(name)) {}

  [[noreturn]] void fail(const std::string& message) const {
    throw SurfaceError(name_ + ":" + std::to_string(line_) + ": " + message);
  }

  double number(std::string_view word) const {
    double value = 0;
    // from_chars does not take a leading '+'; OBJ writers rarely emit one.
    if (!word.empty() && word.front() == '+') word.remove_prefix(1);
    auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), value);
    if (word.empty() || error != std::errc() || end != word.data() + word.size()) {
      fail("expected a number, found '" + std::string(word) + "'");
    }
    return value;
  }

  // A 1-based (or negative, counting back) OBJ index into a list of count items.
  uint32_t index(std::string_view word, std::size_t count, const char* what) const {
    long long value = 0;
    auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), value);
    if (word.empty() || error != std::errc() || end != word.data() + word.size() || value == 0) {
      fail(std::string("expected a ") + what + " index (1-based, or negative), found '" + std::string(word) + "'");
    }
    const long long resolved = value > 0 ? value - 1 : static_cast<long long>(count) + value;
    if (resolved < 0 || resolved >= static_cast<long long>(count)) {
      fail(std::string(what) + " index " + std::to_string(value) + " is out of range (" + std::to_string(count) +
           " defined so far)");
    }
    return static_cast<uint32_t>(resolved);
  }

  void line(std::string_view text) {
    ++line_;
    std::size_t comment = text.find('#');
    if (comment != std::string_view::npos) text = text.substr(0, comment);
    std::string_view rest = text;
    std::string_view keyword = nextWord(rest);
    if (keyword == "v") {
      glm::dvec3 p;
      for (int k = 0; k < 3; ++k) p[k] = number(nextWord(rest));
      if (surface_.positions.size() >= kMaxPositions) fail("more than 16777216 vertices");
      surface_.positions.push_back(p);
    } else if (keyword == "vt") {
      glm::dvec2 t;
      for (int k = 0; k < 2; ++k) t[k] = number(nextWord(rest));
      texcoords_.push_back(t);
    } else if (keyword == "vn") {
      for (int k = 0; k < 3; ++k) number(nextWord(rest));
      ++normals_;
    } else if (keyword == "f") {
      face(rest);
    }
  }

  void face(std::string_view rest) {
    std::vector<uint32_t> corners;
    for (std::string_view word = nextWord(rest); !word.empty(); word = nextWord(rest)) {
      std::size_t slash = word.find('/');
      const uint32_t position = index(word.substr(0, slash), surface_.positions.size(), "vertex");
      if (slash != std::string_view::npos) {
        std::string_view tail = word.substr(slash + 1);
        std::size_t second = tail.find('/');
        std::string_view texcoord = tail.substr(0, second);
        if (!texcoord.empty()) noteTexcoord(position, index(texcoord, texcoords_.size(), "texture coordinate"));
        if (second != std::string_view::npos) index(tail.substr(second + 1), normals_, "normal");
      } else {
        untextured_ = true;
      }
      corners.push_back(position);
    }
    if (corners.size() < 3) fail("a face needs at least 3 vertices, found " + std::to_string(corners.size()));
    for (std::size_t k = 1; k + 1 < corners.size(); ++k) {
      surface_.triangles.push_back({corners[0], corners[k], corners[k + 1]});
    }
  }

  void noteTexcoord(uint32_t position, uint32_t texcoord) {
    if (texcoordOf_.size() <= position) texcoordOf_.resize(position + 1);
    if (texcoordOf_[position] && *texcoordOf_[position] != texcoord) conflicting_ = true;
    texcoordOf_[position] = texcoord;
  }

  Surface finish() {
    if (surface_.triangles.empty()) throw SurfaceError(name_ + ": no faces (an OBJ surface needs 'f' lines)");
    bool everyPosition = !untextured_ && !conflicting_ && texcoordOf_.size() == surface_.positions.size();
    for (const auto& t : texcoordOf_) everyPosition = everyPosition && t.has_value();
    if (everyPosition) {
      for (const auto& t : texcoordOf_) surface_.texcoords.push_back(texcoords_[*t]);
    }
    return std::move(surface_);
  }

 private:
  std::string name_;
  int line_ = 0;
  Surface surface_;
  std::vector<glm::dvec2> texcoords_;
  std::size_t normals_ = 0;
  std::vector<std::optional<uint32_t>> texcoordOf_;
  bool untextured_ = false;
  bool conflicting_ = false;
};

}  // namespace

Surface readObjSurface(std::istream& in, const std::string& name) {
  ObjParser parser(name);
  std::string text;
  while (std::getline(in, text)) parser.line(text);
  if (in.bad()) throw SurfaceError(name + ": read error");
  return parser.finish();
}

Surface loadObjSurface(const std::filesystem::path& path) {
  std::error_code error;
  const std::filesystem::file_status status = std::filesystem::status(path, error);
  if (std::filesystem::is_directory(status)) throw SurfaceError("cannot read surface " + path.string() + ": it is a directory");
  // Asked before opening: a FIFO would block, a device never end.
  if (std::filesystem::exists(status) && !std::filesystem::is_regular_file(status))
    throw SurfaceError("cannot read surface " + path.string() + ": it is not a regular file");
  std::ifstream in(path);
  if (!in) throw SurfaceError("cannot read surface " + path.string() + ": no such file or not readable");
  return readObjSurface(in, path.string());
}

}  // namespace ontogen
