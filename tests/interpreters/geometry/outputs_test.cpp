// Every output format of the geometry set, read back by independent programs: the
// Khronos glTF validator (npm, in .tools/), assimp (Debian assimp-utils), libpng and
// ffprobe (Debian ffmpeg).
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include "interpreters/formats/glb_writer.h"
#include "interpreters/formats/movie_writer.h"
#include "interpreters/formats/renderer.h"
#include "interpreters/geometry/geometry_set.h"
#include "interpreters/geometry/surface.h"
#include "tests/interpreters/external_tools.h"
#include "tests/interpreters/png_decode.h"
#include "tests/checkers.h"

namespace ontogen {
namespace {

namespace fs = std::filesystem;

using testing_support::reported;
using testing_support::runCommand;

/// The path of the validator's node module folder, or "" when it is not installed.
std::string validatorModules() {
  fs::path modules = fs::path(ONTOGEN_SOURCE_DIR) / ".tools" / "node_modules";
  if (!fs::exists(modules / "gltf-validator" / "package.json")) return "";
  if (runCommand("command -v node >/dev/null 2>&1").first != 0) return "";
  return modules.string();
}

/// Runs the Khronos validator on a .glb; returns its exit status and report.
std::pair<int, std::string> validateGlb(const fs::path& file) {
  fs::path script = fs::path(ONTOGEN_SOURCE_DIR) / "tests" / "interpreters" / "validate_gltf.js";
  return runCommand("node '" + script.string() + "' '" + validatorModules() + "' '" + file.string() + "' 2>&1");
}

using Decoded = testing_support::DecodedPng;
using testing_support::decodePng;

class OutputsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    directory_ = fs::temp_directory_path() /
                 ("ontogen_outputs_test_" + std::to_string(::getpid()) + "_" +
                  ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(directory_);
    fs::create_directories(directory_);
  }
  void TearDown() override { fs::remove_all(directory_); }

  /// Draws a small plant: a tube, a branch cylinder, a sphere, a disc and lines, in colours.
  static void draw(GeometrySet& set, double bend) {
    auto x = [&](const char* c, std::vector<double> args = {}) { set.execute(c, args); };
    x("!", {0.3});
    x("gcbegin");
    x("F", {2});
    x("+", {bend});
    x("F", {2});
    x("[");
    x("color", {1});
    x("&", {40});
    x("!", {0.1});
    x("F", {1.5});
    x("sphere", {0.3});
    x("]");
    x("F", {1});
    x("gcend");
    x("color", {3});
    x("disc", {0.8});
    x("!", {0});
    x("F", {1});
    x("+", {30});
    x("F", {1});
  }

  std::vector<fs::path> runFrames(const std::string& formats, int frames) {
    GeometrySetDef def;
    EXPECT_EQ(applyGeometryFormats(formats, def.output), "");
    def.output.render.width = 160;
    def.output.render.height = 120;
    GeometrySet set(def);
    std::vector<fs::path> all;
    for (int f = 0; f < frames; ++f) {
      set.beginFrame({.directory = directory_, .stem = "plant", .frame = f, .frameCount = frames, .time = 0.5 * f});
      draw(set, 10.0 + 10 * f);
      for (auto& path : set.endFrame()) all.push_back(path);
    }
    return all;
  }

  fs::path directory_;
};

TEST_F(OutputsTest, FormatsAreParsedAndUnknownOnesNamed) {
  SceneOutputDef def;
  EXPECT_EQ(applyGeometryFormats("glb,png", def), "");
  EXPECT_TRUE(def.writeGlb && def.writePng);
  EXPECT_FALSE(def.writeSvg || def.writeObj || def.writePly || def.writeMp4 || def.writePngFrames);
  EXPECT_EQ(applyGeometryFormats("obj,gltf", def),
            "unknown format 'gltf' (known: glb, png, png-frames, mp4, obj, ply, ply-ascii, svg, joints, mjcf, or none alone)");
  EXPECT_EQ(applyGeometryFormats("ply-ascii", def), "");
  EXPECT_TRUE(def.writePly && !def.plyBinary);
  EXPECT_EQ(applyGeometryFormats("ply", def), "");
  EXPECT_TRUE(def.writePly && def.plyBinary);
  EXPECT_EQ(applyGeometryFormats("ply,ply-ascii", def),
            "the formats 'ply' and 'ply-ascii' write the same file (<model>.ply); choose one");
}

TEST_F(OutputsTest, AnimatedGlbPassesTheKhronosValidator) {
  std::vector<fs::path> written = runFrames("glb", 4);
  ASSERT_EQ(written.size(), 1u);
  EXPECT_EQ(written[0], directory_ / "plant.glb");
  ONTOGEN_REQUIRE_CHECKER(!validatorModules().empty(), "gltf-validator not installed (bash .ci/setup installs it)");
  auto [status, report] = validateGlb(written[0]);
  EXPECT_EQ(status, 0) << report;
  EXPECT_NE(report.find("errors 0"), std::string::npos) << report;
  // assimp reads it too, with the four frames' meshes.
  auto [assimpStatus, info] = runCommand("assimp info '" + written[0].string() + "' 2>&1");
  EXPECT_EQ(assimpStatus, 0) << info;
}

TEST_F(OutputsTest, BlendedSurfacesAndFilteredPlatesPassTheKhronosValidator) {
  // Two 4 x 4 patches of one topology (a flat one and a dome) blended by weights that
  // change from frame to frame, and a plate sheet joined by the gap filter.
  auto patch = [](double height) {
    PatchControls c;
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < 4; ++i) c[4 * j + i] = glm::dvec3(i, j, (i == 1 || i == 2) && (j == 1 || j == 2) ? height : 0);
    return bezierPatch(c, 4);
  };
  GeometrySetDef def;
  ASSERT_EQ(applyGeometryFormats("glb", def.output), "");
  def.turtle.surfaces[0] = patch(0);
  def.turtle.surfaces[1] = patch(3);
  GeometrySet set(def);
  std::vector<fs::path> written;
  for (int f = 0; f < 3; ++f) {
    set.beginFrame({.directory = directory_, .stem = "blend", .frame = f, .frameCount = 3, .time = 1.0 * f});
    auto x = [&](const char* c, std::vector<double> args = {}) { set.execute(c, args); };
    x("color", {5});
    x("blend", {0.5, 0, 2.0 - f, 1, 1.0 * f});
    x("attractor", {1, 1, 2, 0.05, 2});
    x("gapfilter", {0.3});
    for (int k = 0; k < 4; ++k) {
      x("plate"); x("F"); x("+", {120}); x("F"); x("endplate"); x("-", {120});
      x("plate"); x("F"); x("-", {120}); x("F"); x("endplate"); x("+", {120});
    }
    for (auto& path : set.endFrame()) written.push_back(path);
  }
  EXPECT_EQ(set.geometry().triangleCount(), 32u + 8u);
  ASSERT_EQ(written.size(), 1u);
  ONTOGEN_REQUIRE_CHECKER(!validatorModules().empty(), "gltf-validator not installed (bash .ci/setup installs it)");
  auto [status, report] = validateGlb(written[0]);
  EXPECT_EQ(status, 0) << report;
  EXPECT_NE(report.find("errors 0"), std::string::npos) << report;
}

TEST_F(OutputsTest, EmptyAndSingleFrameGlbsAreValid) {
  GeometrySetDef def;
  applyGeometryFormats("glb", def.output);
  GeometrySet set(def);
  set.beginFrame({.directory = directory_, .stem = "empty"});
  std::vector<fs::path> written = set.endFrame();
  ASSERT_EQ(written.size(), 1u);
  std::vector<fs::path> single = runFrames("glb", 1);
  ONTOGEN_REQUIRE_CHECKER(!validatorModules().empty(), "gltf-validator not installed");
  EXPECT_EQ(validateGlb(written[0]).first, 0) << validateGlb(written[0]).second;
  EXPECT_EQ(validateGlb(single[0]).first, 0) << validateGlb(single[0]).second;
}

TEST_F(OutputsTest, ObjWithMtlLoadsInAssimpWithTheRightCounts) {
  std::vector<fs::path> written = runFrames("obj", 1);
  ASSERT_EQ(written.size(), 2u);
  EXPECT_EQ(written[1], directory_ / "plant.mtl");
  std::ifstream mtl(written[1]);
  std::string text((std::istreambuf_iterator<char>(mtl)), {});
  EXPECT_NE(text.find("newmtl ontogen_0\nKd 0.62 0.55 0.45"), std::string::npos) << text;
  EXPECT_NE(text.find("newmtl ontogen_3"), std::string::npos);
  ONTOGEN_REQUIRE_CHECKER(runCommand("command -v assimp >/dev/null 2>&1").first == 0, "assimp not found");
  auto [status, info] = runCommand("assimp info '" + written[0].string() + "' 2>&1");
  ASSERT_EQ(status, 0) << info;
  // Compare with the geometry drawn again: faces are triangles plus lines.
  GeometrySet set;
  set.beginFrame({.directory = directory_, .stem = "again"});
  draw(set, 10);
  set.endFrame();
  EXPECT_EQ(reported(info, "Faces"), static_cast<long>(set.geometry().triangleCount() + set.geometry().segmentCount()))
      << info;
  EXPECT_EQ(reported(info, "Materials"), 3) << info;  // the colours used: 0, 1, 3
}

TEST_F(OutputsTest, PlyLoadsInAssimp) {
  std::vector<fs::path> written = runFrames("ply", 1);
  ASSERT_EQ(written.size(), 1u);
  ONTOGEN_REQUIRE_CHECKER(runCommand("command -v assimp >/dev/null 2>&1").first == 0, "assimp not found");
  auto [status, info] = runCommand("assimp info '" + written[0].string() + "' 2>&1");
  ASSERT_EQ(status, 0) << info;
  GeometrySet set;
  set.beginFrame({.directory = directory_, .stem = "again"});
  draw(set, 10);
  set.endFrame();
  EXPECT_EQ(reported(info, "Faces"), static_cast<long>(set.geometry().triangleCount())) << info;
}

TEST_F(OutputsTest, PngHasTheSizeAndShowsTheModel) {
  std::vector<fs::path> written = runFrames("png", 3);
  ASSERT_EQ(written.size(), 1u);  // the last frame only
  EXPECT_EQ(written[0], directory_ / "plant.png");
  Decoded png = decodePng(written[0]);
  ASSERT_TRUE(png.ok);
  EXPECT_EQ(png.width, 160);
  EXPECT_EQ(png.height, 120);
  int model = 0;
  for (std::size_t i = 0; i < png.rgb.size(); i += 3) {
    if (png.rgb[i] != kBackground[0] || png.rgb[i + 1] != kBackground[1] || png.rgb[i + 2] != kBackground[2]) ++model;
  }
  // The model fills a good part of the picture and not all of it.
  EXPECT_GT(model, 160 * 120 / 20);
  EXPECT_LT(model, 160 * 120 * 9 / 10);
  // The centre column holds the model (it is framed around its bounding box).
  std::vector<fs::path> frames = runFrames("png-frames", 2);
  ASSERT_EQ(frames.size(), 2u);
  EXPECT_EQ(frames[1], directory_ / "plant_0001.png");
}

TEST_F(OutputsTest, RendererFramesAFlatDrawingFromTheFront) {
  Geometry square;
  square.addSegment({0, 0, 0}, {1, 0, 0});
  square.addSegment({1, 0, 0}, {1, 1, 0});
  square.addSegment({1, 1, 0}, {0, 1, 0});
  square.addSegment({0, 1, 0}, {0, 0, 0});
  RenderDef def;
  def.width = def.height = 100;
  def.margin = 0.1;
  Image image = renderGeometry(square, def);
  auto dark = [&](int x, int y) { return image.rgb[(static_cast<std::size_t>(y) * 100 + x) * 3] < 200; };
  // The square's sides lie 10 pixels in from each edge; its inside is empty.
  EXPECT_TRUE(dark(10, 50));
  EXPECT_TRUE(dark(89, 50) || dark(90, 50));
  EXPECT_TRUE(dark(50, 10));
  EXPECT_TRUE(dark(50, 89) || dark(50, 90));
  EXPECT_FALSE(dark(50, 50));
  EXPECT_FALSE(dark(3, 3));
  def.width = 0;
  EXPECT_THROW(renderGeometry(square, def), std::invalid_argument);
}

TEST_F(OutputsTest, Mp4HasOneFramePerRunFrame) {
  ONTOGEN_REQUIRE_CHECKER(ffmpegAvailable(), "ffmpeg not installed (Debian package ffmpeg)");
  std::vector<fs::path> written = runFrames("mp4", 5);
  ASSERT_EQ(written.size(), 1u);
  EXPECT_EQ(written[0], directory_ / "plant.mp4");
  auto [status, frames] = runCommand("ffprobe -v error -count_frames -select_streams v:0 -show_entries "
                                     "stream=nb_read_frames -of csv=p=0 '" + written[0].string() + "'");
  ASSERT_EQ(status, 0) << frames;
  EXPECT_EQ(std::stoi(frames), 5);
  // The temporary frames are gone.
  int files = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator(directory_)) ++files;
  EXPECT_EQ(files, 1);
}

}  // namespace
}  // namespace ontogen
