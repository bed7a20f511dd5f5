#include "interpreters/geometry/geometry_set.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <unistd.h>

#include "interpreters/formats/obj_writer.h"
#include "interpreters/formats/svg_writer.h"

namespace ontogen {
namespace {

namespace fs = std::filesystem;

class GeometrySetTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    directory_ = fs::temp_directory_path() /
                 ("ontogen_" + std::string(info->name()) + "_" + std::to_string(::getpid()));
    fs::remove_all(directory_);
    fs::create_directories(directory_);
  }
  void TearDown() override { fs::remove_all(directory_); }

  static std::string read(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
  }

  /// Draws F+F with a branch and an unmatched ].
  static void drawWord(GeometrySet& set) {
    const double ten[] = {10};
    set.execute("F", {});
    set.execute("+", {});
    set.execute("[", {});
    set.execute("!", std::vector<double>{0.5});
    set.execute("F", ten);
    set.execute("]", {});
    set.execute("]", {});
    set.execute("F", {});
    set.execute("unknown", {});
  }

  fs::path directory_;
};

TEST_F(GeometrySetTest, NameAndKnownCommands) {
  GeometrySet set;
  EXPECT_EQ(set.name(), "geometry");
  for (const char* command : {"F", "f", "+", "-", "[", "]", "!", "cC", "disc", "sphere", "$"}) {
    EXPECT_TRUE(set.knows(command)) << command;
  }
  EXPECT_FALSE(set.knows("A"));
  EXPECT_FALSE(set.knows("setColor"));
}

TEST_F(GeometrySetTest, SingleFrameWritesStemSvgAndObj) {
  GeometrySet set;
  set.beginFrame({.directory = directory_, .stem = "plant"});
  drawWord(set);
  std::vector<fs::path> written = set.endFrame();
  ASSERT_EQ(written.size(), 2u);
  EXPECT_EQ(written[0], directory_ / "plant.svg");
  EXPECT_EQ(written[1], directory_ / "plant.obj");

  const Geometry& geometry = set.geometry();
  EXPECT_EQ(geometry.segmentCount(), 2u);
  EXPECT_EQ(geometry.cylinders().size(), 1u);
  EXPECT_EQ(set.warnings().unmatchedPops, 1);

  std::ostringstream svg;
  writeSvg(geometry, svg);
  EXPECT_EQ(read(written[0]), svg.str());
  std::ostringstream obj;
  writeObj(geometry, obj);
  EXPECT_EQ(read(written[1]), obj.str());
  int files = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator(directory_)) ++files;
  EXPECT_EQ(files, 2);
}

TEST_F(GeometrySetTest, SeveralFramesGetNumberedNames) {
  GeometrySet set;
  set.beginFrame({.directory = directory_, .stem = "piston", .frame = 3, .frameCount = 10});
  drawWord(set);
  std::vector<fs::path> written = set.endFrame();
  ASSERT_EQ(written.size(), 2u);
  EXPECT_EQ(written[0], directory_ / "piston_0003.svg");
  EXPECT_EQ(written[1], directory_ / "piston_0003.obj");
  EXPECT_TRUE(fs::is_regular_file(written[0]));
  EXPECT_TRUE(fs::is_regular_file(written[1]));
  EXPECT_EQ(GeometrySet::outputPath({.directory = "d", .stem = "s", .frame = 0, .frameCount = 2},
                                    "svg"),
            fs::path("d") / "s_0000.svg");
  EXPECT_EQ(GeometrySet::outputPath(
                {.directory = "d", .stem = "s", .frame = 12345, .frameCount = 20000}, "obj"),
            fs::path("d") / "s_12345.obj");
}

TEST_F(GeometrySetTest, BeginFrameStartsAfresh) {
  GeometrySet set(GeometrySetDef{.output = {.writeSvg = false}});
  set.beginFrame({.directory = directory_, .stem = "a", .frame = 0, .frameCount = 2});
  drawWord(set);
  set.endFrame();
  set.beginFrame({.directory = directory_, .stem = "a", .frame = 1, .frameCount = 2});
  EXPECT_TRUE(set.geometry().empty());
  EXPECT_EQ(set.warnings().unmatchedPops, 0);
  set.execute("F", {});
  ASSERT_EQ(set.geometry().segmentCount(), 1u);
  EXPECT_EQ(set.geometry().segments()[0].start, glm::dvec3(0, 0, 0));
  EXPECT_EQ(set.geometry().segments()[0].end, glm::dvec3(0, 1, 0));
  std::vector<fs::path> written = set.endFrame();
  ASSERT_EQ(written.size(), 1u);
  EXPECT_EQ(written[0], directory_ / "a_0001.obj");
  EXPECT_FALSE(fs::exists(directory_ / "a_0001.svg"));
}

TEST_F(GeometrySetTest, TurtleDefIsUsed) {
  GeometrySet set(GeometrySetDef{.turtle = {.step = 2, .angle = 45, .radius = 0.1},
                                 .output = {.writeSvg = false, .writeObj = false}});
  set.beginFrame({.directory = directory_, .stem = "a"});
  set.execute("+", {});
  set.execute("F", {});
  EXPECT_TRUE(set.endFrame().empty());
  ASSERT_EQ(set.geometry().cylinders().size(), 1u);
  const CylinderPrimitive& c = set.geometry().cylinders()[0];
  EXPECT_EQ(c.radius, 0.1);
  EXPECT_NEAR(c.end.x, -std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(c.end.y, std::sqrt(2.0), 1e-12);
}

TEST_F(GeometrySetTest, MissingDirectoryThrowsOutputError) {
  GeometrySet set;
  set.beginFrame({.directory = directory_ / "missing", .stem = "a"});
  set.execute("F", {});
  EXPECT_THROW(set.endFrame(), OutputError);
  EXPECT_FALSE(fs::exists(directory_ / "missing"));
}

TEST_F(GeometrySetTest, InvalidDefIsRejected) {
  EXPECT_THROW(GeometrySet(GeometrySetDef{.output = {.svg = {.hairline = -1}}}), std::invalid_argument);
  EXPECT_THROW(GeometrySet(GeometrySetDef{.mesh = {.discSides = 0}}), std::invalid_argument);
  EXPECT_THROW(GeometrySet(GeometrySetDef{.turtle = {.radius = -1}}), std::invalid_argument);
}

}  // namespace
}  // namespace ontogen
