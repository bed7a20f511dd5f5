// A movie keeps one camera for the whole run: a model that grows is seen to grow (its
// size in pixels rises frame by frame) instead of being re-framed into a zoom.

#include <filesystem>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "interpreters/formats/movie_writer.h"
#include "interpreters/formats/renderer.h"
#include "interpreters/formats/scene_output.h"
#include "interpreters/run.h"
#include "tests/checkers.h"
#include "tests/core/test_support.h"
#include "tests/interpreters/external_tools.h"
#include "tests/interpreters/png_decode.h"

namespace ontogen {
namespace {

namespace fs = std::filesystem;
using testing_support::runCommand;

// The height in pixels of what a picture shows: the rows holding a pixel that is not the
// renderer's background (the movie's compression moves colours a little, hence the margin).
long drawnHeight(const testing_support::DecodedPng& png) {
  int top = png.height, bottom = -1;
  for (int y = 0; y < png.height; ++y)
    for (int x = 0; x < png.width; ++x) {
      const uint8_t* p = &png.rgb[(static_cast<std::size_t>(y) * png.width + x) * 3];
      if (std::abs(p[0] - kBackground[0]) + std::abs(p[1] - kBackground[1]) + std::abs(p[2] - kBackground[2]) > 60) {
        top = std::min(top, y);
        bottom = std::max(bottom, y);
      }
    }
  return bottom < 0 ? 0 : bottom - top + 1;
}

TEST(Movie, TheFlowerGrowsUnderOneCamera) {
  ONTOGEN_REQUIRE_CHECKER(ffmpegAvailable(), "ffmpeg not installed (Debian package ffmpeg)");
  const fs::path out = fs::temp_directory_path() / ("ontogen_movie_test_" + std::to_string(::getpid()));
  fs::remove_all(out);
  RunDef def;
  // Named by its absolute path: its #surface files are read beside it.
  def.program = testing_support::compileOrFail(testing_support::readModel("flower.cell"),
                                               std::string(ONTOGEN_SOURCE_DIR) + "/models/flower.cell");
  def.stem = "flower";
  def.frames = 6;
  def.setOptions.formats = "mp4";
  def.setOptions.render.width = 160;
  def.setOptions.render.height = 160;
  def.out = out;
  const RunReport report = ontogen::Run(std::move(def)).execute();
  ASSERT_TRUE(report.ok()) << (report.diagnostics.empty() ? "" : report.diagnostics.front().message);
  ASSERT_TRUE(fs::exists(out / "flower.mp4"));
  // ffmpeg, an independent decoder, takes the movie apart into its frames.
  const auto [status, log] = runCommand("ffmpeg -v error -i '" + (out / "flower.mp4").string() + "' '" +
                                        (out / "frame_%02d.png").string() + "' 2>&1");
  ASSERT_EQ(status, 0) << log;
  std::vector<long> drawn;
  for (int f = 1; fs::exists(out / ("frame_0" + std::to_string(f) + ".png")); ++f)
    drawn.push_back(drawnHeight(testing_support::decodePng(out / ("frame_0" + std::to_string(f) + ".png"))));
  ASSERT_EQ(drawn.size(), 6u);
  // At t = 0 nothing is drawn yet; from t = 2 the stem grows and the heads open (and close
  // a little at the end). Framed on the union of every frame, the early flower is a
  // fraction of the grown one's height and the heights rise; re-framed each frame, every
  // frame fills the picture's height alike (here 125 to 135 pixels of 160).
  std::string sizes;
  for (long d : drawn) sizes += std::to_string(d) + " ";
  EXPECT_EQ(drawn[0], 0) << sizes;
  EXPECT_LT(drawn[1] * 2, drawn[4]) << sizes;
  for (std::size_t f = 2; f < 5; ++f) EXPECT_GT(drawn[f], drawn[f - 1]) << sizes;
  fs::remove_all(out);
}

TEST(Movie, AOneFrameMovieIsWarnedOf) {
  ONTOGEN_REQUIRE_CHECKER(ffmpegAvailable(), "ffmpeg not installed (Debian package ffmpeg)");
  const fs::path out = fs::temp_directory_path() / ("ontogen_movie_short_" + std::to_string(::getpid()));
  fs::remove_all(out);
  RunDef def;
  def.program = testing_support::compileModel("koch.cell");
  def.stem = "koch";
  def.frames = 1;
  def.setOptions.formats = "mp4";
  def.setOptions.render.width = 64;
  def.setOptions.render.height = 64;
  def.out = out;
  const RunReport report = ontogen::Run(std::move(def)).execute();
  ASSERT_TRUE(report.ok());
  bool warned = false;
  for (const RunDiagnostic& d : report.diagnostics)
    warned = warned || (d.severity == Severity::Warning && d.message.find("the movie has one frame") != std::string::npos);
  EXPECT_TRUE(warned);
  fs::remove_all(out);
}

// What ffprobe, an independent reader, says of a movie: frames decoded, and seconds.
struct Probed {
  int frames = -1;
  double seconds = -1;
  std::string log;
};
Probed probe(const fs::path& movie) {
  Probed probed;
  auto [status, text] = runCommand("ffprobe -v error -count_frames -select_streams v:0 -show_entries "
                                   "stream=nb_read_frames,avg_frame_rate:format=duration -of default=nw=1 '" +
                                   movie.string() + "' 2>&1");
  probed.log = text;
  if (status != 0) return probed;
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("nb_read_frames=", 0) == 0) probed.frames = std::stoi(line.substr(15));
    if (line.rfind("duration=", 0) == 0) probed.seconds = std::stod(line.substr(9));
  }
  return probed;
}

// Koch's curve grows for 4 s (#until 4). A run that writes a movie.
RunReport kochMovie(const fs::path& out, std::optional<double> speed, double fps, std::optional<int> frames = {}) {
  fs::remove_all(out);
  RunDef def;
  def.program = testing_support::compileModel("koch.cell");
  def.stem = "koch";
  def.speed = speed;
  def.frames = frames;
  def.setOptions.formats = "mp4";
  def.setOptions.framesPerSecond = fps;
  def.setOptions.render.width = 32;
  def.setOptions.render.height = 32;
  def.out = out;
  return ontogen::Run(std::move(def)).execute();
}

// A second of movie shows `speed` seconds of growth: 4 s at 2 s a second is a 2-second
// movie, at 10 frames a second 21 frames (20 intervals and the last), 2.1 s as ffprobe
// counts a frame's display time.
TEST(Movie, FramesFollowTheSpeedAndTheFrameRate) {
  ONTOGEN_REQUIRE_CHECKER(ffmpegAvailable(), "ffmpeg not installed (Debian package ffmpeg)");
  const fs::path out = fs::temp_directory_path() / ("ontogen_movie_speed_" + std::to_string(::getpid()));
  const RunReport report = kochMovie(out, 2.0, 10);
  ASSERT_TRUE(report.ok()) << (report.diagnostics.empty() ? "" : report.diagnostics.front().message);
  const Probed probed = probe(out / "koch.mp4");
  EXPECT_EQ(probed.frames, 21) << probed.log;
  EXPECT_NEAR(probed.seconds, 2.1, 0.01) << probed.log;
  // Twice the speed, half the movie; 20 frames a second, twice the frames a second.
  ASSERT_TRUE(kochMovie(out, 4.0, 20).ok());
  const Probed fast = probe(out / "koch.mp4");
  EXPECT_EQ(fast.frames, 21) << fast.log;
  EXPECT_NEAR(fast.seconds, 1.05, 0.01) << fast.log;
  fs::remove_all(out);
}

// Nothing says how many frames: a movie of a model that grows is kDefaultMovieSeconds
// long (101 frames at 25 a second), not one frame; #speed in the program is the speed.
TEST(Movie, ADefaultRunWritesAMovieLongEnoughToSee) {
  ONTOGEN_REQUIRE_CHECKER(ffmpegAvailable(), "ffmpeg not installed (Debian package ffmpeg)");
  const fs::path out = fs::temp_directory_path() / ("ontogen_movie_default_" + std::to_string(::getpid()));
  const RunReport report = kochMovie(out, std::nullopt, 25);
  ASSERT_TRUE(report.ok());
  for (const RunDiagnostic& d : report.diagnostics) EXPECT_NE(d.severity, Severity::Warning) << d.message;
  const Probed probed = probe(out / "koch.mp4");
  EXPECT_EQ(probed.frames, static_cast<int>(kDefaultMovieSeconds * 25) + 1) << probed.log;
  EXPECT_NEAR(probed.seconds, kDefaultMovieSeconds + 0.04, 0.01) << probed.log;

  fs::remove_all(out);
  RunDef def;
  def.program = testing_support::compileOrFail("#speed 10\nlsystem k {\n  #until 4\n  axiom F\n  F -> F + F\n}\n");
  def.setOptions.formats = "mp4";
  def.setOptions.render.width = def.setOptions.render.height = 16;
  def.out = out;
  def.stem = "k";
  ASSERT_TRUE(ontogen::Run(std::move(def)).execute().ok());
  EXPECT_EQ(probe(out / "k.mp4").frames, 11);  // 4 s at 10 s a second: 0.4 s at 25 frames a second, and the last
  fs::remove_all(out);
}

TEST(Movie, ASpeedThatMakesTooManyFramesIsRefused) {
  const fs::path out = fs::temp_directory_path() / ("ontogen_movie_many_" + std::to_string(::getpid()));
  const RunReport report = kochMovie(out, 1e-6, 25);
  EXPECT_EQ(report.status, RunStatus::BadDefinition);
  ASSERT_FALSE(report.diagnostics.empty());
  EXPECT_EQ(report.diagnostics.front().message,
            "a speed of 1e-06 s a second over 4 s at 25 frames a second makes 100000001 frames, more than 1000000: "
            "a larger --speed or a lower --fps");
  EXPECT_FALSE(fs::exists(out));
}

// A speed far below any sensible one names the count of frames in a few digits, not the
// 303 digits of 4 / 1e-300 * 25 written in full.
TEST(Movie, ASpeedOfTinySecondsNamesItsFramesInAFewDigits) {
  const fs::path out = fs::temp_directory_path() / ("ontogen_movie_tiny_" + std::to_string(::getpid()));
  const RunReport report = kochMovie(out, 1e-300, 25);
  EXPECT_EQ(report.status, RunStatus::BadDefinition);
  ASSERT_EQ(report.diagnostics.size(), 1u);
  EXPECT_EQ(report.diagnostics.front().message,
            "a speed of 1e-300 s a second over 4 s at 25 frames a second makes 1e+302 frames, more than 1000000: "
            "a larger --speed or a lower --fps");
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace
}  // namespace ontogen
