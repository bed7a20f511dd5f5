#include "interpreters/formats/ply_writer.h"

#include <bit>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "interpreters/formats/mesh_batches.h"
#include "interpreters/geometry/turtle.h"
#include "interpreters/palette.h"
#include "tests/checkers.h"
#include "tests/interpreters/external_tools.h"

namespace ontogen {
namespace {

using testing_support::runCommand;

Geometry plant() {
  Turtle turtle;
  Geometry geometry;
  auto x = [&](const char* command, std::vector<double> args = {}) { turtle.execute(command, args, geometry); };
  x("!", {0.3});
  x("F", {2});
  x("color", {1});
  x("&", {40});
  x("F", {1.5});
  x("sphere", {0.3});
  x("color", {3});
  x("disc", {0.8});
  return geometry;
}

struct PlyVertex {
  glm::vec3 position, normal;
  glm::vec2 texcoord;
  uint8_t rgb[3];
};

/// A PLY file read back by a reader that knows only the layout writePly states: the
/// header's lines, then vertices and faces in ASCII or binary little-endian.
struct PlyFile {
  std::vector<std::string> header;
  std::vector<PlyVertex> vertices;
  std::vector<std::array<uint32_t, 3>> faces;
  std::string error;
};

PlyFile parsePly(const std::string& bytes) {
  PlyFile ply;
  std::size_t at = 0;
  std::size_t vertices = 0, faces = 0;
  while (true) {
    const std::size_t end = bytes.find('\n', at);
    if (end == std::string::npos) return ply.error = "no end_header", ply;
    ply.header.push_back(bytes.substr(at, end - at));
    at = end + 1;
    std::istringstream line(ply.header.back());
    std::string word, kind;
    line >> word;
    if (word == "element") {
      line >> kind;
      (kind == "vertex" ? vertices : faces) = 0;
      line >> (kind == "vertex" ? vertices : faces);
    }
    if (word == "end_header") break;
  }
  const bool binary = ply.header.at(1) == "format binary_little_endian 1.0";
  if (binary) {
    auto u8 = [&]() -> uint32_t { return static_cast<uint8_t>(bytes.at(at++)); };
    auto u32 = [&] {
      uint32_t v = 0;
      for (int shift = 0; shift < 32; shift += 8) v |= u8() << shift;
      return v;
    };
    auto f32 = [&] { return std::bit_cast<float>(u32()); };
    for (std::size_t i = 0; i < vertices; ++i) {
      PlyVertex v;
      v.position = {f32(), f32(), f32()};
      v.normal = {f32(), f32(), f32()};
      v.texcoord = {f32(), f32()};
      for (uint8_t& c : v.rgb) c = static_cast<uint8_t>(u8());
      ply.vertices.push_back(v);
    }
    for (std::size_t i = 0; i < faces; ++i) {
      if (u8() != 3) return ply.error = "not a triangle", ply;
      ply.faces.push_back({u32(), u32(), u32()});
    }
    if (at != bytes.size()) ply.error = "bytes after the last face";
    return ply;
  }
  std::istringstream in(bytes.substr(at));
  for (std::size_t i = 0; i < vertices; ++i) {
    PlyVertex v;
    int r = 0, g = 0, b = 0;
    in >> v.position.x >> v.position.y >> v.position.z >> v.normal.x >> v.normal.y >> v.normal.z >> v.texcoord.x >>
        v.texcoord.y >> r >> g >> b;
    v.rgb[0] = static_cast<uint8_t>(r), v.rgb[1] = static_cast<uint8_t>(g), v.rgb[2] = static_cast<uint8_t>(b);
    ply.vertices.push_back(v);
  }
  for (std::size_t i = 0; i < faces; ++i) {
    int n = 0;
    std::array<uint32_t, 3> f{};
    in >> n >> f[0] >> f[1] >> f[2];
    if (n != 3) return ply.error = "not a triangle", ply;
    ply.faces.push_back(f);
  }
  if (!in) ply.error = "short file";
  return ply;
}

std::string plyOf(const Geometry& geometry, const PlyOptions& options) {
  std::ostringstream out;
  writePly(geometry, out, options);
  return out.str();
}

uint8_t channel(double v) { return static_cast<uint8_t>(std::lround(v * 255)); }

// Binary by default, every value as the batches hold it, bit for bit, with the palette's
// colours; faces index the vertices of their batch.
TEST(PlyWriterTest, BinaryReadsBackByValue) {
  const Geometry geometry = plant();
  const std::string bytes = plyOf(geometry, {});
  const PlyFile ply = parsePly(bytes);
  ASSERT_EQ(ply.error, "");
  EXPECT_EQ(ply.header.at(1), "format binary_little_endian 1.0");
  const std::vector<MeshBatch> batches = batchByMaterial(geometry);
  ASSERT_EQ(batches.size(), 3u);  // colours 0, 1 and 3
  std::size_t v = 0, f = 0;
  for (const MeshBatch& b : batches) {
    const Color c = paletteColor(b.material);
    const std::size_t base = v;
    for (std::size_t i = 0; i < b.positions.size(); ++i, ++v) {
      ASSERT_LT(v, ply.vertices.size());
      EXPECT_EQ(ply.vertices[v].position, b.positions[i]);
      EXPECT_EQ(ply.vertices[v].normal, b.normals[i]);
      EXPECT_EQ(ply.vertices[v].texcoord, b.texcoords[i]);
      EXPECT_EQ(ply.vertices[v].rgb[0], channel(c.r));
      EXPECT_EQ(ply.vertices[v].rgb[1], channel(c.g));
      EXPECT_EQ(ply.vertices[v].rgb[2], channel(c.b));
    }
    for (std::size_t i = 0; i < b.indices.size(); i += 3, ++f) {
      ASSERT_LT(f, ply.faces.size());
      for (int k = 0; k < 3; ++k) EXPECT_EQ(ply.faces[f][k], base + b.indices[i + k]);
    }
  }
  EXPECT_EQ(v, ply.vertices.size());
  EXPECT_EQ(f, geometry.triangleCount());
  // 35 bytes a vertex and 13 a face after the header.
  EXPECT_EQ(bytes.size() - bytes.find("end_header\n") - 11, 35 * ply.vertices.size() + 13 * ply.faces.size());
}

TEST(PlyWriterTest, AsciiHoldsTheSameValues) {
  const Geometry geometry = plant();
  const PlyFile binary = parsePly(plyOf(geometry, {.binary = true}));
  const PlyFile ascii = parsePly(plyOf(geometry, {.binary = false}));
  ASSERT_EQ(ascii.error, "");
  EXPECT_EQ(ascii.header.at(1), "format ascii 1.0");
  ASSERT_EQ(ascii.vertices.size(), binary.vertices.size());
  for (std::size_t i = 0; i < ascii.vertices.size(); ++i) {
    // Nine significant digits hold a float exactly.
    EXPECT_EQ(ascii.vertices[i].position, binary.vertices[i].position) << i;
    EXPECT_EQ(ascii.vertices[i].normal, binary.vertices[i].normal) << i;
    EXPECT_EQ(ascii.vertices[i].rgb[1], binary.vertices[i].rgb[1]) << i;
  }
  EXPECT_EQ(ascii.faces, binary.faces);
}

// Z-up: (x, y, z) -> (x, -z, y) for positions and normals; the faces keep their order.
TEST(PlyWriterTest, ZUpTurnsAQuarterAboutX) {
  const Geometry geometry = plant();
  const PlyFile y = parsePly(plyOf(geometry, {}));
  const PlyFile z = parsePly(plyOf(geometry, {.up = UpAxis::Z}));
  ASSERT_EQ(z.error, "");
  EXPECT_EQ(z.header.at(2), "comment ontogen geometry, z up");
  ASSERT_EQ(z.vertices.size(), y.vertices.size());
  for (std::size_t i = 0; i < y.vertices.size(); ++i) {
    const glm::vec3 p = y.vertices[i].position, n = y.vertices[i].normal;
    EXPECT_EQ(z.vertices[i].position, glm::vec3(p.x, 0.0f - p.z, p.y)) << i;
    EXPECT_EQ(z.vertices[i].normal, glm::vec3(n.x, 0.0f - n.z, n.y)) << i;
  }
  EXPECT_EQ(z.faces, y.faces);
}

// assimp reads the binary file: its faces, and its bounds, which in the z-up file stand
// on z: the stem's 2 units (and the branch above) rise along +z.
TEST(PlyWriterTest, AssimpReadsBinaryAndZUp) {
  ONTOGEN_REQUIRE_CHECKER(runCommand("command -v assimp >/dev/null 2>&1").first == 0,
                          "assimp not found (Debian package assimp-utils)");
  const Geometry geometry = plant();
  const std::filesystem::path path =
      std::filesystem::temp_directory_path() / ("ontogen_ply_test_" + std::to_string(::getpid()) + ".ply");
  auto bounds = [&](UpAxis up) {
    std::ofstream(path, std::ios::binary) << plyOf(geometry, {.up = up});
    auto [status, info] = runCommand("assimp info '" + path.string() + "' 2>&1");
    EXPECT_EQ(status, 0) << info;
    EXPECT_EQ(testing_support::reported(info, "Faces"), static_cast<long>(geometry.triangleCount())) << info;
    glm::dvec3 max{0.0};
    const std::size_t at = info.find("Maximum point");
    EXPECT_NE(at, std::string::npos) << info;
    if (at != std::string::npos) std::sscanf(info.c_str() + at, "Maximum point (%lf %lf %lf)", &max.x, &max.y, &max.z);
    return max;
  };
  const glm::dvec3 yUp = bounds(UpAxis::Y), zUp = bounds(UpAxis::Z);
  std::filesystem::remove(path);
  const Box& box = geometry.bounds();
  EXPECT_NEAR(yUp.y, box.max.y, 1e-4);
  EXPECT_NEAR(zUp.z, box.max.y, 1e-4);
  EXPECT_NEAR(zUp.y, -box.min.z, 1e-4);
  EXPECT_NEAR(zUp.x, yUp.x, 1e-6);
}

}  // namespace
}  // namespace ontogen
