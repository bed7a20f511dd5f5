// Predefined surfaces: the OBJ reader, Bezier patches, blends, and their placement by
// the turtle (surface, blend, patch ... endpatch).
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "interpreters/geometry/obj_reader.h"
#include "interpreters/geometry/surface.h"
#include "interpreters/geometry/turtle.h"

namespace ontogen {
namespace {

// A unit square in the x-y plane as a quad (triangulated to 2), with texture coordinates
// and normals, comments and statements the reader skips.
constexpr const char* kSquare = R"(# a square
mtllib none.mtl
o square
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
vt 0 0
vt 1 0
vt 1 1
vt 0 1
vn 0 0 1
usemtl x
s off
f 1/1/1 2/2/1 3/3/1 -1/4/1
)";

Surface read(const std::string& text) {
  std::istringstream in(text);
  return readObjSurface(in, "test.obj");
}

std::string errorOf(const std::string& text) {
  try {
    read(text);
  } catch (const SurfaceError& error) {
    return error.what();
  }
  return "";
}

TEST(ObjReaderTest, ReadsVerticesTexcoordsAndTriangulatesPolygons) {
  Surface s = read(kSquare);
  ASSERT_EQ(s.positions.size(), 4u);
  ASSERT_EQ(s.triangles.size(), 2u);
  EXPECT_EQ(s.triangles[0], (std::array<uint32_t, 3>{0, 1, 2}));
  EXPECT_EQ(s.triangles[1], (std::array<uint32_t, 3>{0, 2, 3}));  // -1 is the last vertex
  ASSERT_EQ(s.texcoords.size(), 4u);
  EXPECT_EQ(s.texcoords[2], glm::dvec2(1, 1));
  EXPECT_EQ(s.positions[2], glm::dvec3(1, 1, 0));
}

TEST(ObjReaderTest, BadFilesNameTheLineAndTheProblem) {
  EXPECT_EQ(errorOf("v 0 0 0\nv 1 0 0\nf 1 2 3\n"), "test.obj:3: vertex index 3 is out of range (2 defined so far)");
  EXPECT_EQ(errorOf("v 0 zero 0\n"), "test.obj:1: expected a number, found 'zero'");
  EXPECT_EQ(errorOf("v 0 0 0\nv 1 0 0\nf 1 2\n"), "test.obj:3: a face needs at least 3 vertices, found 2");
  EXPECT_EQ(errorOf("v 0 0 0\n"), "test.obj: no faces (an OBJ surface needs 'f' lines)");
  EXPECT_EQ(errorOf("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1//2 2 3\n"),
            "test.obj:4: normal index 2 is out of range (0 defined so far)");
  try {
    loadObjSurface("/nonexistent/leaf.obj");
    FAIL() << "no error";
  } catch (const SurfaceError& error) {
    EXPECT_EQ(std::string(error.what()), "cannot read surface /nonexistent/leaf.obj: no such file or not readable");
  }
}

TEST(SurfaceTest, PlacedObjHasItsVerticesScaledIntoTheTurtleFrame) {
  const auto path = std::filesystem::temp_directory_path() / "ontogen_surface_test_square.obj";
  std::ofstream(path) << kSquare;
  TurtleDef def;
  def.surfaces[7] = loadObjSurface(path);
  std::filesystem::remove(path);
  Turtle turtle(def);
  Geometry geometry;
  // At the initial frame surface coordinates are world coordinates; after & 90 the
  // turtle heads along -z (H turns towards -U), so the square's y goes along -z.
  turtle.execute("f", std::vector<double>{2}, geometry);
  turtle.execute("surface", std::vector<double>{7, 3}, geometry);
  ASSERT_EQ(geometry.mesh().positions.size(), 4u);
  EXPECT_EQ(geometry.bounds().min, glm::dvec3(0, 2, 0));
  EXPECT_EQ(geometry.bounds().max, glm::dvec3(3, 5, 0));
  turtle.execute("&", std::vector<double>{90}, geometry);
  turtle.execute("surface", std::vector<double>{7, 2}, geometry);
  ASSERT_EQ(geometry.mesh().positions.size(), 8u);
  const glm::dvec3 far = geometry.mesh().positions[6];  // (1, 1, 0) scaled by 2
  EXPECT_NEAR(far.x, 2, 1e-12);
  EXPECT_NEAR(far.y, 2, 1e-12);
  EXPECT_NEAR(far.z, -2, 1e-12);
  for (const glm::dvec3& n : geometry.mesh().normals) EXPECT_NEAR(glm::length(n), 1.0, 1e-12);
  EXPECT_EQ(turtle.state().position, glm::dvec3(0, 2, 0));  // placing does not move
}

TEST(SurfaceTest, UndefinedSurfaceIsAnError) {
  Turtle turtle;
  Geometry geometry;
  try {
    turtle.execute("surface", std::vector<double>{4}, geometry);
    FAIL() << "no error";
  } catch (const SurfaceError& error) {
    EXPECT_NE(std::string(error.what()).find("surface 4 is not defined"), std::string::npos) << error.what();
  }
}

PatchControls flatPatch(double height) {
  PatchControls c;
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) c[4 * j + i] = glm::dvec3(i, j, (i == 1 || i == 2) && (j == 1 || j == 2) ? height : 0);
  return c;
}

TEST(SurfaceTest, BezierPatchInterpolatesItsCornersAndBulgesByTheBernsteinWeights) {
  Surface s = bezierPatch(flatPatch(4), 4);
  ASSERT_EQ(s.positions.size(), 25u);
  ASSERT_EQ(s.triangles.size(), 32u);
  EXPECT_EQ(s.positions[0], glm::dvec3(0, 0, 0));
  EXPECT_EQ(s.positions[24], glm::dvec3(3, 3, 0));
  // At u = v = 1/2 the four inner points weigh (3/8)^2 each: z = 4 * 4 * 9/64 = 2.25.
  EXPECT_NEAR(s.positions[12].z, 2.25, 1e-12);
  EXPECT_NEAR(s.positions[12].x, 1.5, 1e-12);
  EXPECT_THROW(bezierPatch(flatPatch(0), 0), SurfaceError);
}

TEST(SurfaceTest, BlendWeightsSelectAndAverageVertexByVertex) {
  const Surface a = bezierPatch(flatPatch(0), 3);
  const Surface b = bezierPatch(flatPatch(4), 3);
  const Surface c = bezierPatch(flatPatch(-8), 3);
  const std::vector<const Surface*> three = {&a, &b, &c};
  const Surface first = blendSurfaces(three, std::vector<double>{1, 0, 0});
  EXPECT_EQ(first.positions, a.positions);  // exactly
  EXPECT_EQ(first.triangles, a.triangles);
  const Surface half = blendSurfaces(three, std::vector<double>{0.5, 0.5, 0});
  for (std::size_t i = 0; i < half.positions.size(); ++i) {
    EXPECT_NEAR(glm::length(half.positions[i] - (a.positions[i] + b.positions[i]) / 2.0), 0, 1e-12) << i;
  }
  // Weights are normalised: (2, 2, 0) is the same average.
  const Surface scaled = blendSurfaces(three, std::vector<double>{2, 2, 0});
  EXPECT_EQ(scaled.positions, half.positions);
  EXPECT_THROW(blendSurfaces(three, std::vector<double>{0, 0, 0}), SurfaceError);
}

TEST(SurfaceTest, BlendOfDifferentTopologiesIsAnError) {
  const Surface coarse = bezierPatch(flatPatch(0), 3);
  const Surface fine = bezierPatch(flatPatch(0), 4);
  const std::vector<const Surface*> both = {&coarse, &fine};
  try {
    blendSurfaces(both, std::vector<double>{1, 1});
    FAIL() << "no error";
  } catch (const SurfaceError& error) {
    EXPECT_EQ(std::string(error.what()),
              "surfaces 1 and 2 of the blend have different topologies (16 and 25 vertices, 18 and 32 triangles); a "
              "blend needs the same vertices and triangles in every surface");
  }
}

TEST(SurfaceTest, TurtlePatchCommandsDefineASurfaceForTheFrame) {
  Turtle turtle;
  Geometry geometry;
  auto x = [&](const char* c, std::vector<double> args = {}) { turtle.execute(c, args, geometry); };
  x("patch", {3, 2});
  for (const glm::dvec3& p : flatPatch(4)) x("patchpoint", {p.x, p.y, p.z});
  x("endpatch");
  ASSERT_NE(turtle.surface(3), nullptr);
  x("surface", {3, 1});
  EXPECT_EQ(geometry.mesh().positions.size(), 9u);
  EXPECT_NEAR(geometry.bounds().max.z, 2.25, 1e-12);
  // The blend of the patch with itself is the patch.
  x("blend", {1, 3, 0.3, 3, 0.7});
  ASSERT_EQ(geometry.mesh().positions.size(), 18u);
  for (std::size_t i = 0; i < 9; ++i) {
    EXPECT_NEAR(glm::length(geometry.mesh().positions[i] - geometry.mesh().positions[9 + i]), 0, 1e-12);
  }
  // A patch with 15 points is not defined; an even blend argument count is skipped.
  x("patch", {4});
  for (int i = 0; i < 15; ++i) x("patchpoint", {0, 0, 0});
  x("endpatch");
  EXPECT_EQ(turtle.surface(4), nullptr);
  x("blend", {1, 3, 1, 3});
  EXPECT_EQ(turtle.warnings().badArguments, 2);
  turtle.reset();
  EXPECT_EQ(turtle.surface(3), nullptr);  // patches belong to their frame
}

}  // namespace
}  // namespace ontogen
