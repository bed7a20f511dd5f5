#include "interpreters/formats/obj_writer.h"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include <sys/wait.h>
#include <unistd.h>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "interpreters/geometry.h"
#include "interpreters/geometry/turtle.h"
#include "tests/interpreters/external_tools.h"
#include "tests/checkers.h"

namespace ontogen {
namespace {

struct Instruction {
  std::string command;
  std::vector<double> args;
};

Geometry draw(const std::vector<Instruction>& word) {
  Turtle turtle;
  Geometry geometry;
  for (const Instruction& i : word) turtle.execute(i.command, i.args, geometry);
  return geometry;
}

std::string objOf(const Geometry& geometry) {
  std::ostringstream out;
  writeObj(geometry, out);
  return out.str();
}

/// An OBJ file read back by a reader that knows only what writeObj writes; indices
/// are kept 1-based as in the file.
struct ObjFile {
  std::vector<glm::dvec3> vertices;
  std::vector<glm::dvec3> normals;
  std::vector<std::array<std::pair<long, long>, 3>> faces;  // (vertex, normal) per corner
  std::vector<std::pair<long, long>> lines;
  std::vector<std::string> comments;
  std::vector<std::string> errors;
};

ObjFile parseObj(const std::string& text) {
  ObjFile obj;
  std::istringstream in(text);
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    std::istringstream fields(line);
    std::string tag;
    fields >> tag;
    auto error = [&](const std::string& what) {
      obj.errors.push_back(std::to_string(number) + ": " + what + ": " + line);
    };
    if (tag == "#") {
      obj.comments.push_back(line);
    } else if (tag == "v" || tag == "vn") {
      glm::dvec3 v;
      if (!(fields >> v.x >> v.y >> v.z)) error("bad vector");
      (tag == "v" ? obj.vertices : obj.normals).push_back(v);
    } else if (tag == "f") {
      std::array<std::pair<long, long>, 3> face;
      for (auto& [vertex, normal] : face) {
        // "v//n": two numbers around a double slash.
        char slash1 = 0;
        char slash2 = 0;
        if (!(fields >> vertex >> slash1 >> slash2 >> normal) || slash1 != '/' || slash2 != '/') {
          error("bad corner");
        }
      }
      std::string extra;
      if (fields >> extra) error("not a triangle");
      obj.faces.push_back(face);
    } else if (tag == "l") {
      long a = 0;
      long b = 0;
      if (!(fields >> a >> b)) error("bad line");
      obj.lines.push_back({a, b});
    } else {
      error("unexpected tag");
    }
  }
  return obj;
}

/// Checks indices and normals; returns "" or the first problem.
std::string checkObj(const ObjFile& obj) {
  if (!obj.errors.empty()) return obj.errors.front();
  const long vertices = static_cast<long>(obj.vertices.size());
  const long normals = static_cast<long>(obj.normals.size());
  for (const auto& face : obj.faces) {
    for (auto [v, n] : face) {
      if (v < 1 || v > vertices) return "vertex index out of range";
      if (n < 1 || n > normals) return "normal index out of range";
    }
  }
  for (auto [a, b] : obj.lines) {
    if (a < 1 || a > vertices || b < 1 || b > vertices) return "line index out of range";
  }
  for (const glm::dvec3& n : obj.normals) {
    if (std::abs(glm::length(n) - 1) > 1e-9) return "normal not unit length";
  }
  return "";
}

/// Every undirected edge in exactly two faces, once in each direction (closed and
/// consistently wound). Returns "" or the first problem.
std::string checkWatertight(const ObjFile& obj) {
  std::map<std::pair<long, long>, int> directed;
  for (const auto& face : obj.faces) {
    for (int k = 0; k < 3; ++k) ++directed[{face[k].first, face[(k + 1) % 3].first}];
  }
  for (const auto& [edge, count] : directed) {
    if (count != 1) return "edge used twice in one direction";
    auto reverse = directed.find({edge.second, edge.first});
    if (reverse == directed.end()) return "edge in only one face (a hole)";
  }
  return directed.empty() ? "no faces" : "";
}

TEST(ObjWriterTest, CountsMatchTheGeometryAndTheHeader) {
  Geometry geometry = draw({{"F", {}}, {"F", {}}, {"+", {}}, {"F", {}}, {"f", {}}, {"F", {}},
                            {"!", {0.5}}, {"F", {}}, {"cC", {2, 1}}, {"disc", {1, 2}},
                            {"sphere", {1}}});
  std::string text = objOf(geometry);
  ObjFile obj = parseObj(text);
  ASSERT_EQ(checkObj(obj), "");
  const Mesh& mesh = geometry.mesh();
  // Segments 1-3 form one chain (4 vertices), segment 4 starts after a gap (2 more).
  EXPECT_EQ(obj.vertices.size(), mesh.positions.size() + 6);
  EXPECT_EQ(obj.normals.size(), mesh.normals.size());
  EXPECT_EQ(obj.faces.size(), geometry.triangleCount());
  EXPECT_EQ(obj.lines.size(), geometry.segmentCount());
  EXPECT_EQ(obj.lines.size(), 4u);
  ASSERT_GE(obj.comments.size(), 2u);
  std::ostringstream header;
  header << "# " << obj.vertices.size() << " vertices, " << obj.normals.size() << " normals, "
         << obj.faces.size() << " triangles, 4 line segments";
  EXPECT_EQ(obj.comments[1], header.str());
  // Lines connect the segments' ends.
  for (std::size_t i = 0; i < geometry.segmentCount(); ++i) {
    const Segment& s = geometry.segments()[i];
    EXPECT_LT(glm::length(obj.vertices[obj.lines[i].first - 1] - s.start), 1e-9);
    EXPECT_LT(glm::length(obj.vertices[obj.lines[i].second - 1] - s.end), 1e-9);
  }
  EXPECT_EQ(obj.lines[1].first, obj.lines[0].second);
  EXPECT_NE(obj.lines[3].first, obj.lines[2].second);
}

// The text of a file many times larger than the writer's buffer, line for line as printf
// writes it (%.10g, -0 as 0): numbers and lines are never cut where the buffer is handed
// to the stream.
TEST(ObjWriterTest, ALargeFileIsWrittenAsPrintfWouldWriteIt) {
  Geometry geometry;
  std::string expected = "# ontogen geometry\n# 40000 vertices, 0 normals, 0 triangles, 20000 line segments\n";
  std::string lines;
  auto number = [](double value) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.10g", value);
    return std::string(buffer) == "-0" ? std::string("0") : std::string(buffer);
  };
  for (int i = 0; i < 20'000; ++i) {
    const glm::dvec3 a(std::sin(0.37 * i) * 1e3, -std::cos(1.3 * i) / 7, i % 5 == 0 ? -0.0 : i * 1e-7);
    const glm::dvec3 b = a + glm::dvec3(1.0 / 3, 2e12, -1e-300);
    geometry.addSegment(a, b);
    for (const glm::dvec3& v : {a, b}) expected += "v " + number(v.x) + " " + number(v.y) + " " + number(v.z) + "\n";
    lines += "l " + std::to_string(2 * i + 1) + " " + std::to_string(2 * i + 2) + "\n";
  }
  expected += lines;
  ASSERT_GT(expected.size(), std::size_t{1} << 20);
  EXPECT_TRUE(objOf(geometry) == expected);
}

TEST(ObjWriterTest, FacesWindOutwardsAgreeingWithTheirNormals) {
  Geometry geometry = draw({{"&", {25}}, {"!", {2}}, {"cC", {5, 1}}, {"f", {10}},
                            {"sphere", {3}}, {"f", {10}}, {"disc", {1, 4}}});
  ObjFile obj = parseObj(objOf(geometry));
  ASSERT_EQ(checkObj(obj), "");
  for (const auto& face : obj.faces) {
    const glm::dvec3& a = obj.vertices[face[0].first - 1];
    const glm::dvec3& b = obj.vertices[face[1].first - 1];
    const glm::dvec3& c = obj.vertices[face[2].first - 1];
    glm::dvec3 n = glm::cross(b - a, c - a);
    ASSERT_GT(glm::length(n), 0);
    for (auto [v, k] : face) EXPECT_GT(glm::dot(n, obj.normals[k - 1]), 0);
  }
}

TEST(ObjWriterTest, CappedCylinderIsWatertight) {
  ObjFile obj = parseObj(objOf(draw({{"+", {15}}, {"!", {3}}, {"cC", {10, 1}}})));
  ASSERT_EQ(checkObj(obj), "");
  EXPECT_EQ(checkWatertight(obj), "");
  EXPECT_EQ(obj.faces.size(), 48u);
  EXPECT_EQ(obj.vertices.size(), 26u);
}

TEST(ObjWriterTest, SphereIsWatertightAndOpenCylinderIsNot) {
  ObjFile sphere = parseObj(objOf(draw({{"sphere", {2}}})));
  EXPECT_EQ(checkWatertight(sphere), "");
  ObjFile open = parseObj(objOf(draw({{"!", {3}}, {"F", {10}}})));
  EXPECT_EQ(checkWatertight(open), "edge in only one face (a hole)");
}

TEST(ObjWriterTest, ReadsBackToTheGeometry) {
  Geometry geometry = draw({{"+", {37}}, {"&", {11}}, {"!", {0.3}}, {"F", {1234.5}}});
  ObjFile obj = parseObj(objOf(geometry));
  ASSERT_EQ(obj.vertices.size(), geometry.mesh().positions.size());
  for (std::size_t i = 0; i < obj.vertices.size(); ++i) {
    EXPECT_LT(glm::length(obj.vertices[i] - geometry.mesh().positions[i]), 1e-6);
  }
}

// Z-up: every position and normal turned a quarter about +x, (x, y, z) -> (x, -z, y);
// the faces are the same (a rotation keeps their winding).
TEST(ObjWriterTest, ZUpTurnsPositionsAndNormals) {
  Geometry geometry = draw({{"+", {37}}, {"&", {11}}, {"!", {0.3}}, {"F", {2}}, {"!", {0}}, {"F", {1}}});
  std::ostringstream zUp;
  writeObj(geometry, zUp, UpAxis::Z);
  ObjFile y = parseObj(objOf(geometry)), z = parseObj(zUp.str());
  ASSERT_EQ(checkObj(z), "");
  ASSERT_EQ(z.vertices.size(), y.vertices.size());
  ASSERT_EQ(z.normals.size(), y.normals.size());
  ASSERT_FALSE(z.vertices.empty());
  for (std::size_t i = 0; i < y.vertices.size(); ++i) {
    EXPECT_EQ(z.vertices[i], glm::dvec3(y.vertices[i].x, -y.vertices[i].z, y.vertices[i].y)) << i;
  }
  for (std::size_t i = 0; i < y.normals.size(); ++i) {
    EXPECT_EQ(z.normals[i], glm::dvec3(y.normals[i].x, -y.normals[i].z, y.normals[i].y)) << i;
  }
  EXPECT_EQ(z.faces, y.faces);
  EXPECT_EQ(z.lines, y.lines);
  EXPECT_EQ(z.comments.front(), "# ontogen geometry, z up");
  // The line's end, 3 units up the tilted turtle, rises along +y in the world and +z in
  // the z-up file.
  EXPECT_GT(geometry.segments().back().end.y, 2);
  EXPECT_NEAR(z.vertices.back().z, geometry.segments().back().end.y, 1e-9);
  EXPECT_NEAR(z.vertices.back().y, -geometry.segments().back().end.z, 1e-9);
}

using testing_support::reported;
using testing_support::runCommand;

// Whether a checker is there: a test skips without it, except on CI, where it fails.
bool haveTool(const std::string& name) {
  if (runCommand("command -v " + name + " >/dev/null 2>&1").first == 0) return true;
  const char* ci = std::getenv("CI");
  if (ci != nullptr && std::string(ci) == "true") ADD_FAILURE() << name << " is missing on CI";
  return false;
}

// Readers refuse an OBJ without a mesh: empty geometry is one point at the origin.
TEST(ObjWriterTest, EmptyGeometryIsOnePointThatAssimpReads) {
  EXPECT_EQ(objOf(Geometry{}),
            "# ontogen geometry\n# 0 vertices, 0 normals, 0 triangles, 0 line segments\n"
            "# nothing to draw in this frame: one point at the origin\nv 0 0 0\np 1\n");
  ONTOGEN_REQUIRE_CHECKER(haveTool("assimp"), "assimp not found (Debian package assimp-utils)");
  const std::filesystem::path path =
      std::filesystem::temp_directory_path() / ("ontogen_empty_" + std::to_string(::getpid()) + ".obj");
  std::ofstream(path) << objOf(Geometry{});
  auto [status, info] = runCommand("assimp info '" + path.string() + "' 2>&1");
  std::filesystem::remove(path);
  EXPECT_EQ(status, 0) << info;
  EXPECT_EQ(reported(info, "Meshes"), 1) << info;
}

TEST(ObjWriterTest, AssimpReadsTheFile) {
  ONTOGEN_REQUIRE_CHECKER(runCommand("command -v assimp >/dev/null 2>&1").first == 0,
                          "assimp not found (Debian package assimp-utils)");
  // Primitives apart from each other, so assimp's vertex joining merges nothing across them.
  Geometry geometry = draw({{"!", {1}}, {"cC", {4, 1}}, {"f", {10}}, {"sphere", {2}}, {"f", {10}},
                            {"disc", {1, 3}}, {"f", {10}}, {"!", {0}}, {"F", {}}, {"F", {}},
                            {"+", {}}, {"F", {}}});
  std::filesystem::path path = std::filesystem::temp_directory_path() /
                               ("ontogen_obj_writer_test_" + std::to_string(::getpid()) + ".obj");
  {
    std::ofstream out(path);
    writeObj(geometry, out);
    ASSERT_TRUE(out.good());
  }
  auto [status, output] = runCommand("assimp info '" + path.string() + "' 2>&1");
  std::filesystem::remove(path);
  ASSERT_EQ(status, 0) << output;
  // assimp counts a line as a face and makes one vertex per distinct (position, normal)
  // corner of the triangles, plus one per line vertex.
  EXPECT_EQ(reported(output, "Faces"),
            static_cast<long>(geometry.triangleCount() + geometry.segmentCount()))
      << output;
  std::set<std::tuple<uint32_t, uint32_t>> corners;
  for (const Triangle& t : geometry.mesh().triangles) {
    for (int k = 0; k < 3; ++k) corners.insert({t.position[k], t.normal[k]});
  }
  const long lineVertices = 4;  // one chain of three segments
  EXPECT_EQ(reported(output, "Vertices"), static_cast<long>(corners.size()) + lineVertices)
      << output;
}

}  // namespace
}  // namespace ontogen
