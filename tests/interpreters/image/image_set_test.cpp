// The image set: a grid painted site by site through the colour map, read back by libpng.

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <unistd.h>
#include <vector>

#include "core/world.h"
#include "interpreters/image/image_set.h"
#include "interpreters/interpret.h"
#include "lang/compiler.h"
#include "tests/interpreters/png_decode.h"
#include "interpreters/formats/movie_writer.h"
#include "tests/checkers.h"
#include "tests/interpreters/external_tools.h"

namespace ontogen {
namespace {

namespace fs = std::filesystem;
using testing_support::decodePng;

TEST(ImageSet, ColourMapRunsFromDarkBlueToYellow) {
  EXPECT_EQ(colourMap(0), (std::array<uint8_t, 3>{68, 1, 84}));
  EXPECT_EQ(colourMap(1), (std::array<uint8_t, 3>{253, 231, 37}));
  EXPECT_EQ(colourMap(0.5), (std::array<uint8_t, 3>{33, 145, 140}));
  EXPECT_EQ(colourMap(-3), colourMap(0));
  EXPECT_EQ(colourMap(7), colourMap(1));
  EXPECT_EQ(colourMap(std::nan("")), (std::array<uint8_t, 3>{0, 0, 0}));
}

// A 4 x 2 grid whose cells paint their x / 3: each site becomes a square block, row 0 at
// the bottom of the picture, with exactly the colour map's colour.
TEST(ImageSet, EachSiteIsASquareOfItsColour) {
  DiagnosticSink sink;
  auto program = compileSource("img.cell",
                               "cell C { interpret image { range(0, 3) pixel(me.x, me.y, me.x + 10 * me.y) } }\n"
                               "system g { pool grid(4, 2); fill C; }\n",
                               sink);
  ASSERT_NE(program, nullptr) << formatDiagnostics(sink);
  World world(std::shared_ptr<const Program>(std::move(program)));
  const fs::path dir = fs::temp_directory_path() / ("ontogen_image_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  ImageSet set;
  auto written = interpretFrame(world, set, FrameTarget{dir, "img", 0, 1, 0});
  ASSERT_EQ(written.size(), 1u);
  EXPECT_EQ(set.sites().size(), 8u);
  auto png = decodePng(written[0]);
  ASSERT_TRUE(png.ok);
  EXPECT_EQ(png.width, 512);  // 4 sites, 128 pixels each
  EXPECT_EQ(png.height, 256);
  auto pixel = [&](int x, int y) {
    const size_t at = (static_cast<size_t>(y) * png.width + x) * 3;
    return std::array<uint8_t, 3>{png.rgb[at], png.rgb[at + 1], png.rgb[at + 2]};
  };
  for (int sx = 0; sx < 4; ++sx) {
    // Bottom row: y = 0, value sx / 3; top row: y = 1, value above the range.
    EXPECT_EQ(pixel(sx * 128 + 64, 192), colourMap(sx / 3.0)) << sx;
    EXPECT_EQ(pixel(sx * 128 + 5, 130), colourMap(sx / 3.0)) << sx;
    EXPECT_EQ(pixel(sx * 128 + 64, 64), colourMap(1)) << sx;
  }
  fs::remove_all(dir);
}

// A site outside any picture is the program's error, located at its instruction.
TEST(ImageSet, ASiteOutsideThePictureIsALocatedInstructionError) {
  ImageSet set;
  set.beginFrame(FrameTarget{fs::temp_directory_path(), "x", 0, 1, 0});
  set.locate({SourceSpan{}, "C", 2.5});
  for (const std::array<double, 3>& at : {std::array<double, 3>{1e6, 0, 0}, {-5, -5, 1}, {NAN, 0, 0}, {0, INFINITY, 0}}) {
    try {
      set.execute("pixel", at);
      FAIL() << at[0] << ", " << at[1];
    } catch (const InstructionError& error) {
      EXPECT_EQ(error.cell, "C");
      EXPECT_EQ(error.time, 2.5);
      EXPECT_NE(std::string(error.what()).find("is outside the picture: a site's coordinates are whole numbers 0 to 8191"),
                std::string::npos)
          << error.what();
    }
  }
  const double edge[3] = {8191, 8191, 0};
  EXPECT_NO_THROW(set.execute("pixel", edge));
}

// A picture is at most 512 pixels along its longer side (or one pixel a site).
TEST(ImageSet, ATallGridMakesAPictureNoTallerThanAWideOneIsWide) {
  ImageSet set;
  set.beginFrame(FrameTarget{fs::temp_directory_path(), "x", 0, 1, 0});
  const double top[3] = {0, 1000, 0};
  set.execute("pixel", top);
  const Image image = set.picture();
  EXPECT_EQ(image.width, 1);
  EXPECT_EQ(image.height, 1001);
}

}  // namespace
}  // namespace ontogen

namespace ontogen {
namespace {

// With mp4 the frames go into one movie, which ffmpeg, an independent decoder, reads back
// frame by frame with the pictures' colours: a grid whose colour moves with time.
TEST(ImageSet, Mp4MakesOneMovieOfEveryFrame) {
  ONTOGEN_REQUIRE_CHECKER(ffmpegAvailable(), "ffmpeg not installed (Debian package ffmpeg)");
  DiagnosticSink sink;
  auto program = compileSource("movie.cell",
                               "cell C { interpret image { range(0, 3) pixel(me.x, me.y, age) } }\n"
                               "system g { pool grid(4, 4); fill C; }\n",
                               sink);
  ASSERT_NE(program, nullptr) << formatDiagnostics(sink);
  World world(std::shared_ptr<const Program>(std::move(program)));
  const fs::path dir = fs::temp_directory_path() / ("ontogen_image_movie_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  ImageSet set(ImageSetDef{.pictures = false, .movie = true, .framesPerSecond = 25});
  std::vector<fs::path> written;
  for (int frame = 0; frame < 4; ++frame) {
    world.advanceTo(frame, 1);
    for (const fs::path& path : interpretFrame(world, set, FrameTarget{dir, "movie", frame, 4, double(frame)}))
      written.push_back(path);
  }
  ASSERT_EQ(written.size(), 1u);
  EXPECT_EQ(written[0], dir / "movie.mp4");
  int files = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator(dir)) ++files;
  EXPECT_EQ(files, 1);  // no pictures, no frames left behind
  const auto [status, log] = testing_support::runCommand("ffmpeg -v error -i '" + written[0].string() + "' '" +
                                                         (dir / "f%d.png").string() + "' 2>&1");
  ASSERT_EQ(status, 0) << log;
  for (int frame = 0; frame < 4; ++frame) {
    auto png = decodePng(dir / ("f" + std::to_string(frame + 1) + ".png"));
    ASSERT_TRUE(png.ok) << frame;
    const std::array<uint8_t, 3> expected = colourMap(frame / 3.0);
    const size_t centre = (static_cast<size_t>(png.height / 2) * png.width + png.width / 2) * 3;
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(png.rgb[centre + c], expected[c], 12) << "frame " << frame << " channel " << c;
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace ontogen
