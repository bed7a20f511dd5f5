#pragma once
// An MP4 movie of pictures, through ffmpeg (H.264, yuv420p): the pictures are written as
// PNGs into a hidden folder beside the movie (removed on SIGINT and SIGTERM too, and when
// the movie is made), then encoded at once; the movie appears complete or not at all.
// The geometry's output stage and the image set both make their movies with it.

#include <filesystem>
#include <memory>
#include <string>

#include "interpreters/formats/renderer.h"
#include "interpreters/temporary_files.h"

namespace ontogen {

/// True when an executable named ffmpeg is on PATH.
bool ffmpegAvailable();

class MovieWriter {
 public:
  /// The movie `path` (DIR/<stem>.mp4) at framesPerSecond (> 0).
  MovieWriter(std::filesystem::path path, double framesPerSecond);
  ~MovieWriter();
  MovieWriter(const MovieWriter&) = delete;
  MovieWriter& operator=(const MovieWriter&) = delete;

  /// Adds the next picture. Throws OutputError when it cannot be kept.
  void addFrame(const Image& image);
  int frameCount() const { return frames_; }
  /// Encodes the pictures added into the movie and removes them. Throws OutputError
  /// (ffmpeg failed, or the file cannot be renamed into place).
  void finish();

 private:
  std::filesystem::path path_;
  std::filesystem::path folder_;
  double framesPerSecond_;
  int frames_ = 0;
  std::unique_ptr<RegisteredTemporary> registered_;
};

}  // namespace ontogen
